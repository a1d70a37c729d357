# Fails when a file includes a folder it may not (docs/ARCHITECTURE.md "The three floors"):
# engine/ includes no other floor; fem, cutting, surface, haptics, render, metrics, contact and
# recording include only engine; batch/ and trainee/ (beside app/ on the top floor, which
# composes nothing) include only engine too, and only app/ includes them; window/ (beside app/ as
# well: the trainee window's parts) includes engine and the domains, and only app/ and replay/
# include it; replay/ and bench/suite/ stand on top of app/, and only the command line's main
# (app/main.cpp) includes them; python/ (the module on top of app/) is included by no floor.
cmake_policy(SET CMP0057 NEW)  # if(IN_LIST) in script mode
set(domains fem cutting surface haptics render metrics contact recording)
set(beside_app batch trainee)
set(bad "")
foreach(folder engine ${domains} ${beside_app} window app)
  file(GLOB_RECURSE files ${ROOT}/${folder}/*.h ${ROOT}/${folder}/*.cpp ${ROOT}/${folder}/*.cu
                          ${ROOT}/${folder}/*.cuh)
  foreach(f ${files})
    file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
    foreach(line ${lines})
      string(REGEX MATCH "\"([a-z_]+)/" m "${line}")
      set(target "${CMAKE_MATCH_1}")
      if(target STREQUAL "" OR target STREQUAL folder OR target STREQUAL "engine")
        continue()
      endif()
      if(target STREQUAL "python")
        list(APPEND bad "${f}: ${line}")
      elseif(folder STREQUAL "window")
        # Beside app/: the domains it composes, nothing beside or above it.
        if(NOT target IN_LIST domains)
          list(APPEND bad "${f}: ${line}")
        endif()
      elseif(target STREQUAL "window" AND NOT folder STREQUAL "app")
        list(APPEND bad "${f}: ${line}")
      elseif((target STREQUAL "replay" OR target STREQUAL "bench") AND
             NOT f STREQUAL "${ROOT}/app/main.cpp")
        # On top of app/: only the command line's main registers their commands.
        list(APPEND bad "${f}: ${line}")
      elseif(NOT folder STREQUAL "app" AND (target STREQUAL "app" OR target IN_LIST domains OR
                                            target IN_LIST beside_app))
        list(APPEND bad "${f}: ${line}")
      endif()
    endforeach()
  endforeach()
endforeach()
if(bad)
  list(JOIN bad "\n" msg)
  message(FATAL_ERROR "Floor violations (see docs/ARCHITECTURE.md):\n${msg}")
endif()
message(STATUS "floors respected")
