# Precompiled headers: three header sets, each compiled once per build and reused by every
# target of its kind (REUSE_FROM): the libraries', the programs' (the command, benchmarks) and
# the tests'.
# Parsing Eigen, OpenCV's core, nlohmann/json, yaml-cpp and the standard library took about
# two thirds of each translation unit's compile time (5 of 8 s for a typical test), and most
# units include them: of 310 units, 227 reach Eigen, 185 yaml-cpp, 173 OpenCV's core, 165 json.
# Heavier headers that few units need (Ceres, OpenCV's calib3d) stay out: every unit of a
# target that reuses a header set reads all of it.
#
# A reused header set must be compiled with its users' flags: each set's target links the same
# brdfrig::options and carries the same definitions as its users (GCC refuses a header set
# compiled with a definition its user lacks, clang one whose value differs; one the user adds,
# such as BRDFRIG_BINARY, is fine for both). The fuzz
# targets add -fsanitize=fuzzer and compile without. CMake's own switch turns every set off
# (cmake -DCMAKE_DISABLE_PRECOMPILE_HEADERS=ON), which also shows a file that relies on a
# header it does not include. Users: target_precompile_headers(TARGET REUSE_FROM SET).
set(brdfrig_common_pch_headers
    <algorithm> <array> <cmath> <cstdint> <filesystem> <functional> <map> <memory> <optional>
    <string> <utility> <vector> <iostream> <sstream> <Eigen/Core> <Eigen/Geometry>
    <opencv2/core.hpp> <nlohmann/json.hpp> <yaml-cpp/yaml.h>)

set(brdfrig_pch_anchor ${CMAKE_BINARY_DIR}/brdfrig_pch_anchor.cc)
file(CONFIGURE OUTPUT ${brdfrig_pch_anchor} CONTENT "// compiles the shared precompiled headers\n")

# brdfrig_add_header_set(NAME [PROGRAMS] HEADERS ... DEPS ... DEFINITIONS ...): a header set for
# libraries, or with PROGRAMS for executables: GCC refuses a set compiled as position-independent
# code (-fPIC, a library's) in a position-independent executable (-fPIE) and the other way round.
function(brdfrig_add_header_set name)
  cmake_parse_arguments(ARG "PROGRAMS" "" "HEADERS;DEPS;DEFINITIONS" ${ARGN})
  add_library(${name} STATIC ${brdfrig_pch_anchor})
  target_link_libraries(${name} PRIVATE brdfrig::options ${ARG_DEPS})
  if(ARG_DEFINITIONS)
    target_compile_definitions(${name} PRIVATE ${ARG_DEFINITIONS})
  endif()
  target_precompile_headers(${name} PRIVATE ${ARG_HEADERS})
  if(ARG_PROGRAMS)
    set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE OFF)
    target_compile_options(${name} PRIVATE -fPIE)
  endif()
endfunction()

set(brdfrig_pch_deps Eigen3::Eigen OpenCV::core nlohmann_json::nlohmann_json yaml-cpp)
# The libraries (brdfrig_add_library).
brdfrig_add_header_set(brdfrig_library_headers HEADERS ${brdfrig_common_pch_headers}
                       DEPS ${brdfrig_pch_deps}
                       DEFINITIONS BRDFRIG_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                   BRDFRIG_VERSION="${PROJECT_VERSION}")
# The command (apps/, which defines BRDFRIG_VERSION) and the benchmarks (BRDFRIG_SOURCE_DIR):
# no definitions, as a user may add one the set lacks but not lack one the set has.
brdfrig_add_header_set(brdfrig_program_headers PROGRAMS HEADERS ${brdfrig_common_pch_headers}
                       DEPS ${brdfrig_pch_deps})
# The tests (brdfrig_add_test): the programs' set and GoogleTest.
if(BRDFRIG_BUILD_TESTS)
  brdfrig_add_header_set(brdfrig_test_headers PROGRAMS
                         HEADERS ${brdfrig_common_pch_headers} <gtest/gtest.h>
                         DEPS ${brdfrig_pch_deps} GTest::gtest
                         DEFINITIONS BRDFRIG_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
endif()
