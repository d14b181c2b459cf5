#!/usr/bin/env bash
# Runs the libFuzzer targets (fuzz/, built by the asan preset with clang) over their seed corpora.
#   scripts/fuzz.sh [SECONDS [TARGET...]]     default: 10 s each, every target (CI's smoke run)
# New inputs go to build/asan/fuzz-found/<target>/ (the seeds in fuzz/corpus/ are only read);
# a crash, leak, UB report or timeout stops with the failing input in
# build/asan/fuzz-artifacts/. Each run's last lines (exec count, cov, ft) are in
# build/asan/fuzz-logs/<target>.log.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-10}"
shift || true
cd "$root"
out="${BRDFRIG_FUZZ_BUILD:-build/asan}"  # the build holding fuzz/ (docs/fuzzing.md)
bin=$out/fuzz
[[ -d "$bin" ]] || { echo "fuzz: no $bin: cmake --build --preset asan first" >&2; exit 2; }
if (($# == 0)); then
  mapfile -t targets < <(cd fuzz && ls fuzz_*.cc | sed 's/\.cc$//')
else
  targets=("$@")
fi
mkdir -p $out/fuzz-found $out/fuzz-artifacts $out/fuzz-logs
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
failed=()
for t in "${targets[@]}"; do
  mkdir -p "$out/fuzz-found/$t"
  log="$out/fuzz-logs/$t.log"
  start=$SECONDS
  # -timeout: one input taking longer is a hang; -rss_limit_mb: a bound on what one input may
  # make the parser allocate (the parsers promise bounded sizes).
  if "$bin/$t" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$out/fuzz-artifacts/$t-" "$out/fuzz-found/$t" "fuzz/corpus/$t" \
      >"$log" 2>&1; then
    echo "fuzz: $t ok ($((SECONDS - start)) s): $(grep -E '^#[0-9]+[[:space:]]+DONE' "$log" | tail -1)"
  else
    echo "fuzz: $t FAILED ($((SECONDS - start)) s), see $log:" >&2
    tail -40 "$log" >&2
    failed+=("$t")
  fi
done
if ((${#failed[@]} > 0)); then
  echo "fuzz: ${#failed[@]} target(s) failed: ${failed[*]}" >&2
  exit 1
fi
