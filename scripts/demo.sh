#!/usr/bin/env bash
# The main job: installs missing packages, builds, and runs the built-in demo
# (simulated capture -> reconstruction -> rendering -> report) into ./demo-out.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh" release
cd "$root"
exec build/release/apps/brdfrig demo -o "${1:-demo-out}"
