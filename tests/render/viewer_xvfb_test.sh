#!/usr/bin/env bash
# render/viewer_xvfb_test: `brdfrig view` under Xvfb renders a few frames of two materials side
# by side and saves a screenshot. Passes only when the viewer exits 0, says where it saved the
# screenshot, and the file is a PNG of the window's size (a crash at exit, or a message without
# a file, fails).
#   viewer_xvfb_test.sh BRDFRIG SOURCE_DIR SCREENSHOT
set -uo pipefail
brdfrig="$1" source_dir="$2" shot="$3"
material="$source_dir/tests/data/glossy_slices.json"
rm -f "$shot"
output=$(xvfb-run -a -s "-screen 0 640x360x24" "$brdfrig" view "$material" --compare "$material" \
  --width 640 --height 360 --frames 3 --screenshot "$shot" 2>&1)
status=$?
echo "$output"
fail() {
  echo "viewer_xvfb_test: $*" >&2
  exit 1
}
((status == 0)) || fail "brdfrig view exited with status $status"
grep -q "screenshot: " <<<"$output" || fail "no 'screenshot: ' line in the output"
[[ -s "$shot" ]] || fail "no screenshot at $shot"
# PNG signature, then the IHDR chunk's width and height (big-endian) at bytes 16..23.
[[ "$(od -An -tx1 -N8 "$shot" | tr -d ' \n')" == "89504e470d0a1a0a" ]] || fail "$shot is not a PNG"
size=$(od -An -tu1 -j16 -N8 "$shot" | awk '{print $1*16777216+$2*65536+$3*256+$4 "x" \
  $5*16777216+$6*65536+$7*256+$8}')
[[ "$size" == "640x360" ]] || fail "screenshot is $size, expected 640x360"
echo "viewer_xvfb_test: exit 0, screenshot $shot is a 640x360 PNG"
