#!/usr/bin/env bash
# Renders the sphere of a glTF file with three.js in headless Chromium (software WebGL) and
# writes the page's result (JSON: three.js's reading of the material and the float pixels).
#   three_render.sh MODEL.glb OUT.json 'width=128&height=128&...'   (query: three_render.mjs)
# Exit 0 with OUT written; 1 the page reported an error (on stderr); 2 no result in time.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
model="$(realpath "$1")" out="$2" query="$3"
seconds="${BRDFRIG_BROWSER_SECONDS:-120}"
work="$(mktemp -d)"
server_pid='' browser_pid=''
cleanup() {
  [[ -n "$browser_pid" ]] && kill -- -"$browser_pid" 2>/dev/null
  [[ -n "$server_pid" ]] && kill -- "$server_pid" 2>/dev/null
  wait 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

node "$here/serve.mjs" "$model" "$out" "$seconds" > "$work/port" &
server_pid=$!
for _ in $(seq 100); do
  grep -q '^port ' "$work/port" 2>/dev/null && break
  sleep 0.1
done
port="$(awk '/^port /{print $2}' "$work/port")"
[[ -n "$port" ]] || { echo "three_render: the server did not start" >&2; exit 2; }

# Software WebGL: SwiftShader behind ANGLE (current Chromium asks for the unsafe flag to use it).
setsid chromium --headless=new --no-sandbox --disable-gpu-sandbox --use-angle=swiftshader \
  --enable-unsafe-swiftshader --ignore-gpu-blocklist --no-first-run --disable-extensions \
  --user-data-dir="$work/profile" \
  "http://127.0.0.1:$port/page/three_render.html?model=$(basename "$model")&$query" \
  > "$work/browser.log" 2>&1 &
browser_pid=$!

status=0
wait "$server_pid" || status=$?
server_pid=''
if ((status != 0)); then
  echo "three_render: no rendering (status $status); the browser said:" >&2
  grep -v 'dbus\|Fontconfig' "$work/browser.log" | tail -20 >&2 || true
fi
exit "$status"
