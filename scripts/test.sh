#!/usr/bin/env bash
# The test command: installs missing packages, builds, and runs the whole ctest suite.
#   scripts/test.sh            release build (what CI runs)
#   scripts/test.sh asan       AddressSanitizer + UndefinedBehaviorSanitizer build
# Tests needing lab hardware (label "hardware") are excluded; run them with
#   ctest --preset release -L hardware
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
preset="${1:-release}"
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh" "$preset"
cd "$root"
ctest --preset "$preset" -LE hardware
