#!/usr/bin/env bash
# The test command (CI runs exactly this, see .ci/run): installs missing packages, then runs
# in order, stopping at the first failure, and prints each step's time:
#   release  release build, the whole ctest suite
#   asan     AddressSanitizer + UndefinedBehaviorSanitizer build (clang), the suite but for the
#            tests labelled "accuracy" or "consumers" (release only, see tests/CMakeLists.txt),
#            then
#            every libFuzzer target of the same build for a smoke time over its seed corpus
#            (BRDFRIG_FUZZ_SECONDS, default 5; see docs/fuzzing.md)
#   tsan     ThreadSanitizer build of the threaded parts' tests (ctest label "threads")
# One or more steps alone:  scripts/test.sh release   (the quick check while developing)
#                           scripts/test.sh asan tsan
# Tests needing lab hardware (label "hardware") are excluded; run them with
#   ctest --preset release -L hardware
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
steps=("$@")
((${#steps[@]} > 0)) || steps=(release asan tsan)
bash "$root/scripts/setup.sh"
cd "$root"
times=()
for step in "${steps[@]}"; do
  start=$SECONDS
  echo "test: step $step"
  case "$step" in
    release | debug | asan | tsan)
      bash scripts/build.sh "$step"
      if [[ "$step" == asan ]]; then
        # The accuracy studies in miniature and the glTF consumers (three.js, Blender: programs
        # of their own; the exporter they read is instrumented in the brdf tests) run in release
        # only (tests/CMakeLists.txt, tests/consumers/CMakeLists.txt).
        ctest --preset asan -LE 'hardware|accuracy|consumers'
        bash scripts/fuzz.sh "${BRDFRIG_FUZZ_SECONDS:-5}"
      else
        ctest --preset "$step" -LE hardware
      fi
      ;;
    *)
      echo "test: unknown step '$step' (release, debug, asan or tsan)" >&2
      exit 2
      ;;
  esac
  times+=("$step $((SECONDS - start)) s")
  echo "test: step $step passed in $((SECONDS - start)) s"
done
echo "test: all passed; times: ${times[*]}"
