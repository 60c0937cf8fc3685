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

# ccache, when installed, in front of every compile (FREEPLAY_CCACHE=OFF, or CCACHE_DISABLE=1 for one build, turns it
# off). Its base_dir is the source folder, so the cache keys hold paths relative to the build folder: a second clone,
# a worktree or a CI checkout in another folder gets the same hits.
find_program(CCACHE_PROGRAM ccache)
option(FREEPLAY_CCACHE "Compile through ccache when it is installed" ON)
# The sloppiness lets ccache cache the units that use a precompiled header (ccache's manual, "Precompiled headers").
if(CCACHE_PROGRAM AND FREEPLAY_CCACHE)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env CCACHE_BASEDIR=${PROJECT_SOURCE_DIR}
      CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime ${CCACHE_PROGRAM})
endif()

# Precompiled headers for the libraries with the most units (docs/performance.md, "Compile time"): the third-party
# headers every unit of the library includes anyway (Eigen, nlohmann-json, yaml-cpp, fmt; OpenCV where the library
# uses it), parsed once per library instead of once per unit. FREEPLAY_PCH=OFF builds without them (e.g. to check
# that every file includes what it uses).
option(FREEPLAY_PCH "Precompile the common third-party headers of the largest libraries" ON)
set(FREEPLAY_PCH_COMMON <algorithm> <filesystem> <functional> <map> <memory> <optional> <string> <vector>
    <Eigen/Geometry> <nlohmann/json.hpp> <yaml-cpp/yaml.h> <fmt/format.h>)

# freeplay_precompile_headers(TARGET [HEADERS...]): the common headers and HEADERS precompiled for TARGET's units.
function(freeplay_precompile_headers target)
  if(FREEPLAY_PCH)
    target_precompile_headers(${target} PRIVATE ${FREEPLAY_PCH_COMMON} ${ARGN})
  endif()
endfunction()

# Unity builds (docs/performance.md, "Unity builds"): the libraries' units, the command units of `freeplay-full`
# (CLI11's inline code and static validators, fmt's formatting) and each test executable's units (GoogleTest, the
# libraries' headers), compiled in batches of up to UNITY_BUILD_BATCH_SIZE files per compile instead of one compile
# each, so the inline and template code they share is compiled once per batch. A unit whose file-local names clash
# with a neighbour's, or whose class defined in a header holds a file-local type (GCC's -Wsubobject-linkage), is
# marked SKIP_UNITY_BUILD_INCLUSION in its folder's CMakeLists.txt. FREEPLAY_UNITY=OFF compiles every unit alone
# (e.g. to check that every file includes what it uses).
option(FREEPLAY_UNITY "Compile the libraries, freeplay-full's commands and each test executable as unity builds" ON)

# freeplay_unity_build(TARGET BATCH_SIZE): TARGET's units compiled BATCH_SIZE at a time (with FREEPLAY_UNITY).
function(freeplay_unity_build target batch_size)
  if(FREEPLAY_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${batch_size})
  endif()
endfunction()

# freeplay_add_library(NAME folder SOURCES ... DEPS ...): a library with public headers in <folder>/include.
function(freeplay_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${name} ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  target_compile_options(${name} PRIVATE ${FREEPLAY_WARNINGS})
  target_compile_features(${name} PUBLIC cxx_std_20)
endfunction()

# freeplay_add_headers(NAME DEPS ...): an INTERFACE library of this folder's public headers alone, for the header-only
# parts (name lists, settings structs, enums) that parse-only code includes without linking the library's code; a call
# into one of its compiled functions fails to link.
function(freeplay_add_headers name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  add_library(${name} INTERFACE)
  target_include_directories(${name} INTERFACE ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(${name} INTERFACE ${ARG_DEPS})
endfunction()

# freeplay_add_test(NAME SOURCES ... DEPS ...): one GoogleTest executable registered with ctest (a unity build).
function(freeplay_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  freeplay_unity_build(${name} 8)
  # -O1 for the tests' own code: 15 % less compile time, the same test CPU time (docs/performance.md); the libraries
  # they test keep the build type's flags.
  target_compile_options(${name} PRIVATE $<$<CONFIG:Release>:-O1>)
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
