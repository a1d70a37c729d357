# Compiler warnings, sanitizers and the serosa_add_library helper shared by every folder.

add_library(serosa_warnings INTERFACE)
target_compile_options(serosa_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
    -Wold-style-cast -Wcast-align -Woverloaded-virtual -Wimplicit-fallthrough
    -Wnull-dereference -Wdouble-promotion -Wformat=2>)
if(SEROSA_WERROR)
  target_compile_options(serosa_warnings INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-Werror>)
endif()

if(SEROSA_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()


# serosa_add_library(NAME folder DEPS ...): one static library per folder. Sources are globbed so
# that adding a file needs no CMake edit; the include root is the repository root, so every
# include names its floor: #include "engine/tet_mesh.h".
function(serosa_add_library name)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB_RECURSE srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  if(NOT srcs)  # a folder whose first file has not landed yet: header-only for now
    add_library(serosa_${name} INTERFACE)
    add_library(serosa::${name} ALIAS serosa_${name})
    target_include_directories(serosa_${name} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(serosa_${name} INTERFACE ${ARG_DEPS})
    return()
  endif()
  add_library(serosa_${name} STATIC ${srcs})
  add_library(serosa::${name} ALIAS serosa_${name})
  target_include_directories(serosa_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(serosa_${name} PUBLIC ${ARG_DEPS} PRIVATE serosa_warnings ${ARG_PRIVATE_DEPS})
  set_target_properties(serosa_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
endfunction()
