#!/usr/bin/env bash
# Time for N sessions through a Slurm job array against the local batch on the same machine:
# the scheduler's overhead per task (docs/slurm.md). Needs a running cluster the sbatch on PATH
# reaches (SLURM_CONF) whose nodes are this machine, and a built brdfrig.
#   bench/slurm_overhead.sh N [brdfrig] [extra reconstruct flags...]
# Sessions are N copies of one small simulated capture (2 positions, 320x240); the local
# batch runs as many at once as the node has CPUs, and so does the array (--throttle).
set -euo pipefail
n="${1:?usage: bench/slurm_overhead.sh N [brdfrig] [reconstruct flags...]}"
brdfrig="$(realpath "${2:-build/release/apps/brdfrig}")"
shift $(( $# >= 2 ? 2 : 1 ))
slots="$(sinfo -h -o %c | head -1)"
work="$(mktemp -d "${TMPDIR:-/tmp}/slurm-overhead-XXXXXX")"
trap 'rm -rf "$work"' EXIT
cat > "$work/scene.yaml" <<'YAML'
rig:
  camera: {resolution: [320, 240], focal_length_mm: 10, sensor_width_mm: 7.2, position: [0, 0, 0.5], look_at: [0, 0, 0], up: [0, 1, 0]}
  light: {position: [0, 0, 0.6], intensity: 1.0}
  axes:
    - {name: camera_arm, moves: camera, direction: [1, 0, 0], range_deg: [-85, 85]}
    - {name: light_arm, moves: light, direction: [1, 0, 0], range_deg: [-85, 85]}
  target: {cutout: [0.1, 0.1], paper: [0.3, 0.3], paper_albedo: 0.8}
sample:
  brdf: {model: ggx, alpha: 0.1, f0: 0.8, diffuse: 0.1}
  size: [0.2, 0.2]
background: {albedo: 0.05}
sensor: {format: png16, gain: 16}
render: {supersampling: 2, seed: 1}
capture:
  exposures: [0.001, 0.008, 0.0666667]
  positions: [{camera_arm: 25, light_arm: -25}, {camera_arm: 45, light_arm: -45}]
effects: []
YAML
"$brdfrig" simulate "$work/scene.yaml" -o "$work/one" --no-truth >/dev/null
mkdir "$work/archive"
for i in $(seq -w 1 "$n"); do cp -r "$work/one" "$work/archive/s$i"; done

now() { date +%s.%N; }
rounds="${ROUNDS:-3}"
# Rounds alternate local and Slurm so that a machine's changing load falls on both alike.
for r in $(seq 1 "$rounds"); do
  rm -rf "$work/local" "$work/fits" "$work/job"
  start=$(now)
  "$brdfrig" reconstruct "$work/archive" -o "$work/local" -j "$slots" "$@" 2>/dev/null \
    > "$work/local.txt"
  local_s=$(awk "BEGIN {print $(now) - $start}")
  # Inside brdfrig: each item's own seconds, "(1.4 s)" at the end of its line.
  local_work=$(grep -o '([0-9.]* s)' "$work/local.txt" | tr -d '(s)' | awk '{s += $1} END {print s}')

  start=$(now)
  "$brdfrig" batch prepare "$work/archive" -o "$work/fits" --job-dir "$work/job" \
    --throttle "$slots" --time 30:00 --submit "$@" >/dev/null 2>&1
  "$brdfrig" batch status "$work/job" --wait --interval 0.2 >/dev/null
  slurm_s=$(awk "BEGIN {print $(now) - $start}")
  "$brdfrig" batch collect "$work/job" | tail -1
  slurm_work=$(grep -h '"seconds"' "$work/job/results/"*.json | awk -F: '{s += $2} END {print s}')
  for f in "$work/local"/*/material.json; do
    cmp -s "$f" "$work/fits/$(basename "$(dirname "$f")")/material.json" || echo "DIFFERS: $f"
  done
  # Overhead per task: wall time beyond the work itself spread over the slots, per task.
  awk -v n="$n" -v c="$slots" -v l="$local_s" -v lw="$local_work" -v s="$slurm_s" \
    -v sw="$slurm_work" 'BEGIN {
      printf "round %d: N=%d, %d at once: local batch %.1f s (items %.1f s), Slurm array %.1f s (tasks %.1f s)\n", '"$r"', n, c, l, lw, s, sw
      printf "  beyond the work, per item: local %.2f s, Slurm %.2f s; difference %.2f s per task\n", (l - lw / c) * c / n, (s - sw / c) * c / n, ((s - sw / c) - (l - lw / c)) * c / n
    }'
done
