# Compiler warnings, sanitizers and the helper every library of the project uses.

set(FREEPLAY_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Woverloaded-virtual
    -Wcast-align -Wdouble-promotion -Wimplicit-fallthrough)
if(FREEPLAY_WERROR)
  list(APPEND FREEPLAY_WARNINGS -Werror)
endif()

if(FREEPLAY_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

find_program(CCACHE_PROGRAM ccache)
if(CCACHE_PROGRAM)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${CCACHE_PROGRAM})
endif()

# freeplay_add_library(NAME folder SOURCES ... DEPS ...): a library with public headers in <folder>/include.
function(freeplay_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${name} ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  target_compile_options(${name} PRIVATE ${FREEPLAY_WARNINGS})
  target_compile_features(${name} PUBLIC cxx_std_20)
endfunction()

# freeplay_add_test(NAME SOURCES ... DEPS ...): one GoogleTest executable registered with ctest.
function(freeplay_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
  target_compile_options(${name} PRIVATE ${FREEPLAY_WARNINGS})
  set(properties ENVIRONMENT "FREEPLAY_ASSETS_DIR=${PROJECT_SOURCE_DIR}/assets")
  if(ARG_LABELS)
    # gtest_discover_tests splits list values, so a test gets one label: "slow" wins (the sanitizer step skips it).
    list(GET ARG_LABELS 0 label)
    if("slow" IN_LIST ARG_LABELS)
      set(label slow)
    endif()
    list(APPEND properties LABELS ${label})
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES ${properties})
endfunction()

# freeplay_add_benchmark(NAME SOURCES ... DEPS ...): a Google Benchmark program in build/bench/.
function(freeplay_add_benchmark name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} benchmark::benchmark benchmark::benchmark_main)
  target_compile_options(${name} PRIVATE ${FREEPLAY_WARNINGS})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bench)
endfunction()
