# Compiler flags shared by every target of the project: warnings (as errors in CI) and sanitizers.
add_library(brdfrig_options INTERFACE)
add_library(brdfrig::options ALIAS brdfrig_options)
target_compile_options(brdfrig_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow
                                                 -Wnon-virtual-dtor -Wno-missing-field-initializers)
# GCC 12's -Wrestrict/-Wstringop-overflow fire on std::string concatenation inlined at -O3
# (GCC bug 105329/105651): false positives in libstdc++, not in our code.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options(brdfrig_options INTERFACE -Wno-restrict -Wno-stringop-overflow)
endif()
if(BRDFRIG_WERROR)
  target_compile_options(brdfrig_options INTERFACE -Werror)
endif()
string(TOLOWER "${BRDFRIG_SANITIZE}" brdfrig_sanitize)
set(BRDFRIG_FUZZ OFF)
set(BRDFRIG_TSAN OFF)
if(brdfrig_sanitize STREQUAL "thread")
  set(BRDFRIG_TSAN ON)
  set(brdfrig_sanitizers thread)
elseif(brdfrig_sanitize STREQUAL "fuzzer")
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "BRDFRIG_SANITIZE=fuzzer needs clang (libFuzzer): use the fuzz preset")
  endif()
  set(BRDFRIG_FUZZ ON)
  set(brdfrig_sanitizers address,undefined)
  # Every library gets libFuzzer's coverage instrumentation; only the fuzz targets link its
  # main (fuzz/CMakeLists.txt adds -fsanitize=fuzzer to them).
  target_compile_options(brdfrig_options INTERFACE -fsanitize=fuzzer-no-link)
elseif(BRDFRIG_SANITIZE)
  set(brdfrig_sanitizers address,undefined)
endif()
if(brdfrig_sanitizers)
  # -O1 as ASan recommends: an unoptimized instrumented build runs the reconstruction suites
  # ~20x slower than release, too slow for a routine run.
  target_compile_options(brdfrig_options INTERFACE -fsanitize=${brdfrig_sanitizers}
                                                   -fno-omit-frame-pointer -O1)
  if(NOT BRDFRIG_TSAN)
    target_compile_options(brdfrig_options INTERFACE -fno-sanitize-recover=undefined)
  endif()
  # GCC's -Wmaybe-uninitialized is unreliable with sanitizer instrumentation (false positives
  # inside libstdc++'s std::regex/std::function at -O1); release builds keep the warning.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(brdfrig_options INTERFACE -Wno-maybe-uninitialized)
  endif()
  target_link_options(brdfrig_options INTERFACE -fsanitize=${brdfrig_sanitizers})
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
endfunction()
