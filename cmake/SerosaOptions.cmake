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

# ThreadSanitizer cannot share a process with ASan, hence a build of its own (the tsan preset).
if(SEROSA_SANITIZE_THREAD)
  if(SEROSA_SANITIZE)
    message(FATAL_ERROR "SEROSA_SANITIZE_THREAD and SEROSA_SANITIZE exclude each other")
  endif()
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
  # GCC warns (-Wtsan, an error under SEROSA_WERROR) that TSan does not model
  # std::atomic_thread_fence. The one fence user, engine/seqlock.h, copies its payload through
  # relaxed atomics, which TSan never reports as racing, so the missing fence model cannot hide
  # or invent a race there.
  # With TSan's instrumentation GCC 12 inlines differently and -Wnull-dereference fires inside
  # libstdc++'s std::string as inlined into CLI11 (a false positive the release and asan builds
  # do not show); the check stays on in every other build.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-Wno-tsan>)
    target_compile_options(serosa_warnings INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-Wno-null-dereference>)
  endif()
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
