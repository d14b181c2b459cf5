#!/usr/bin/env bash
# The screenshot of a report in the docs (docs/images/report.png, linked from README.md): the
# demo's report.html rendered by headless Chromium (Debian's `chromium`, scripts/packages.txt).
#   bash scripts/report_screenshot.sh [REPORT_DIR] [OUTPUT_PNG]
# REPORT_DIR defaults to ./demo-out; without a report.html there, the demo is run first
# (scripts/demo.sh: setup, build, `brdfrig demo`, a few minutes on 2 cores). The window is the
# report's first screens: the material on the sphere, the plan's coverage, the BRDF slices.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dir="${1:-$root/demo-out}"
png="${2:-$root/docs/images/report.png}"
width="${REPORT_SCREENSHOT_WIDTH:-1200}"
height="${REPORT_SCREENSHOT_HEIGHT:-2800}"
if [[ ! -f "$dir/report.html" ]]; then
  bash "$root/scripts/demo.sh" "$dir"
fi
command -v chromium >/dev/null || { echo "chromium is not installed (scripts/setup.sh)" >&2; exit 1; }
mkdir -p "$(dirname "$png")"
tmp="$(mktemp --suffix=.png)"
trap 'rm -f "$tmp"' EXIT
# --no-sandbox: containers and CI run as root; --virtual-time-budget: the images are loaded
# before the picture is taken; the profile in a temporary directory leaves $HOME alone.
profile="$(mktemp -d)"
trap 'rm -f "$tmp"; rm -rf "$profile"' EXIT
chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir="$profile" \
  --virtual-time-budget=10000 --window-size="$width,$height" --screenshot="$tmp" \
  "file://$(realpath "$dir")/report.html" >/dev/null 2>&1 || true
if [[ ! -s "$tmp" ]]; then
  echo "chromium wrote no screenshot of $dir/report.html" >&2
  exit 1
fi
mv "$tmp" "$png"
chmod 644 "$png"  # mktemp made it private
echo "$png: ${width}x${height} screenshot of $dir/report.html"
