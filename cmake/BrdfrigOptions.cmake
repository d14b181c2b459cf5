# Compiler flags shared by every target of the project: warnings (as errors in CI) and sanitizers.
add_library(brdfrig_options INTERFACE)
add_library(brdfrig::options ALIAS brdfrig_options)
target_compile_options(brdfrig_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow
                                                 -Wnon-virtual-dtor -Wno-missing-field-initializers)
# GCC 12's -Wrestrict, -Wstringop-overflow, -Wstringop-overread and -Warray-bounds fire on
# std::string concatenation inlined at -O3 (GCC bug 105329/105651): false positives in
# libstdc++, not in our code. GCC hides some as a system header's, but not once the header comes
# from a precompiled one (cmake/BrdfrigPrecompiledHeaders.cmake).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options(brdfrig_options INTERFACE -Wno-restrict -Wno-stringop-overflow
                                                   -Wno-array-bounds -Wno-stringop-overread)
endif()
if(BRDFRIG_WERROR)
  target_compile_options(brdfrig_options INTERFACE -Werror)
endif()
# BRDFRIG_SANITIZE: OFF; ON or address (ASan + UBSan); thread (TSan).
# -O1 throughout as the sanitizers recommend: an unoptimized instrumented build runs the
# reconstruction suites ~20x slower than release, too slow for a routine run. Line tables only
# (-g1): enough for the sanitizers' file:line reports, at a quarter of full debug info's size.
# An ASan build with clang also carries libFuzzer's coverage instrumentation and builds the
# fuzz targets (fuzz/): one instrumented build serves the suite and the fuzzers.
string(TOLOWER "${BRDFRIG_SANITIZE}" brdfrig_sanitize)
set(BRDFRIG_FUZZ OFF)
set(BRDFRIG_TSAN OFF)
if(brdfrig_sanitize STREQUAL "thread")
  set(BRDFRIG_TSAN ON)
  target_compile_options(brdfrig_options INTERFACE -fsanitize=thread -fno-omit-frame-pointer -O1
                                                   -g1)
  target_link_options(brdfrig_options INTERFACE -fsanitize=thread)
elseif(BRDFRIG_SANITIZE)
  target_compile_options(brdfrig_options INTERFACE -fsanitize=address,undefined
                                                   -fno-sanitize-recover=undefined
                                                   -fno-omit-frame-pointer -O1 -g1)
  target_link_options(brdfrig_options INTERFACE -fsanitize=address,undefined)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    set(BRDFRIG_FUZZ ON)
    # Every library gets libFuzzer's edge coverage (a byte counter per edge: cheap enough for
    # the whole suite to run on it); only the fuzz targets link its main (fuzz/CMakeLists.txt
    # adds -fsanitize=fuzzer to them). -fsanitize=fuzzer-no-link would add trace-cmp, a call
    # at every integer comparison, which slows the instrumented suite in every loop; a long
    # fuzzing session adds it on the configure line (docs/fuzzing.md).
    target_compile_options(brdfrig_options INTERFACE
                           -fsanitize-coverage=inline-8bit-counters,pc-table)
  endif()
endif()
# lld links the ~100 test programs (each holding most of the static libraries) several times
# faster than GNU ld, most of all the instrumented ones.
target_link_options(brdfrig_options INTERFACE -fuse-ld=lld)
# Eigen picks its allocator per translation unit: where __SANITIZE_ADDRESS__ is defined (GCC's
# ASan; clang 14 does not define it) it pads and offsets every heap block itself, elsewhere it
# trusts glibc's 16-byte-aligned malloc. Debian's Ceres is a static library built without ASan, so one program would hold both
# kinds of Eigen::Matrix::resize, and the linker keeps whichever it meets first: a matrix
# allocated by Ceres's copy and freed by ours is a heap-buffer-overflow (seen in the designer's
# K × K matrices). Every sanitized unit uses glibc's alignment too, as the uninstrumented Ceres
# does; Eigen still asserts that each block it gets is 16-byte aligned.
if(BRDFRIG_SANITIZE AND NOT BRDFRIG_TSAN)
  target_compile_definitions(brdfrig_options INTERFACE EIGEN_MALLOC_ALREADY_ALIGNED=1)
endif()
# GCC's -Wmaybe-uninitialized is unreliable with sanitizer instrumentation (false positives
# inside libstdc++'s std::regex/std::function at -O1); release builds keep the warning.
if(BRDFRIG_SANITIZE AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(brdfrig_options INTERFACE -Wno-maybe-uninitialized)
endif()

# brdfrig_add_library(NAME SOURCES ... DEPS ...): the one way a folder declares its library,
# exported as brdfrig::NAME with the source root on the include path (#include "brdf/...").
function(brdfrig_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(brdfrig_${name} STATIC ${ARG_SOURCES})
  add_library(brdfrig::${name} ALIAS brdfrig_${name})
  target_include_directories(brdfrig_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(brdfrig_${name} PUBLIC brdfrig::options ${ARG_DEPS}
                                        PRIVATE ${ARG_PRIVATE_DEPS})
  target_compile_definitions(brdfrig_${name} PRIVATE
                             BRDFRIG_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                             BRDFRIG_VERSION="${PROJECT_VERSION}")
  target_precompile_headers(brdfrig_${name} REUSE_FROM brdfrig_library_headers)
  # Unity build: the library's files compiled eight to a unit, so the project's own headers and
  # the templates they instantiate are compiled once per unit instead of once per file (the
  # test command builds every library three times). Names in a file's anonymous namespace must
  # therefore be unique within its library.
  set_target_properties(brdfrig_${name} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
endfunction()
