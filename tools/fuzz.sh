#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan), writes their seed corpora from the OpenArena
# cache and our own outputs, runs each target for SECONDS and prints executions, coverage and
# whether it crashed. Exits 1 when any target crashed (or leaked, or timed out).
#
# Usage: tools/fuzz.sh [SECONDS] [TARGET...]        (default 30 seconds, every target)
# Environment: Q3MAP_FUZZ_BUILD   build folder (default build-fuzz, in the clone; git-ignored)
#              Q3MAP_FUZZ_JOBS    targets run at once (default: number of cores)
#              Q3MAP_DATA_CACHE   the OpenArena cache (default ~/.cache/q3map2-data)
# Everything it writes stays in the build folder: fuzz-corpus/seeds/<target> (regenerated each
# run), fuzz-corpus/work/<target> (inputs libFuzzer found, kept between runs), fuzz-logs/<target>.log
# and fuzz-artifacts/<target>/ (crashing inputs).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

seconds=${1:-30}
[ $# -gt 0 ] && shift
case "$seconds" in ''|*[!0-9]*) echo "fuzz.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 2 ;; esac
all_targets=(bsp sh_runtime map map_bsp shader json json_pack pk3 prt world_lights lightcache)
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${all_targets[@]}")
for t in "${targets[@]}"; do
  case " ${all_targets[*]} " in *" $t "*) ;; *) echo "fuzz.sh: unknown target '$t' (known: ${all_targets[*]})" >&2; exit 2 ;; esac
done

build=${Q3MAP_FUZZ_BUILD:-build-fuzz}
case "$build" in /*) ;; *) build="$root/$build" ;; esac
jobs=${Q3MAP_FUZZ_JOBS:-$(nproc)}
cache=${Q3MAP_DATA_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/q3map2-data}

tools/install-deps.sh build test

echo "== fuzz build ($build)"
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DQ3MAP_FUZZ=ON -DQ3MAP_TESTS=OFF -DQ3MAP_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target fuzz_all

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=0
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1:suppressions=$root/tests/fuzz/ubsan.supp

echo "== seed corpora ($build/fuzz-corpus/seeds)"
seeds="$build/fuzz-corpus/seeds"
rm -rf "$seeds"
"$build/tests/fuzz/fuzz_seed_corpus" "$cache" "$seeds"

logs="$build/fuzz-logs"
scratch="$build/fuzz-tmp"
mkdir -p "$logs" "$scratch"

run_target() {
  local t=$1
  local work="$build/fuzz-corpus/work/$t" artifacts="$build/fuzz-artifacts/$t/"
  local corpora=("$work" "$seeds/$t")
  [ -d "tests/fuzz/regressions/$t" ] && corpora+=("tests/fuzz/regressions/$t")
  mkdir -p "$work" "$artifacts"
  rm -f "$logs/$t.rc"
  local rc=0
  TMPDIR="$scratch" "$build/tests/fuzz/fuzz_$t" -max_total_time="$seconds" -print_final_stats=1 \
    -timeout=30 -rss_limit_mb=2048 -artifact_prefix="$artifacts" "${corpora[@]}" >"$logs/$t.log" 2>&1 || rc=$?
  echo "$rc" >"$logs/$t.rc"
}

echo "== fuzzing ${targets[*]} for ${seconds}s each, $jobs at a time"
running=0
for t in "${targets[@]}"; do
  run_target "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait || true
rm -rf "$scratch"

# Per target: executions and exec/s from the final stats, cov/ft from libFuzzer's last status line.
crashed=0
printf '%-12s %12s %8s %7s %7s  %s\n' target executions exec/s cov ft result
for t in "${targets[@]}"; do
  log="$logs/$t.log"
  rc=$(cat "$logs/$t.rc" 2>/dev/null || echo "no exit status")
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(grep -oE ' cov: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+' || true)
  ft=$(grep -oE ' ft: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+' || true)
  if [ "$rc" = 0 ]; then
    result=ok
  else
    crashed=1
    artifact=$(grep -oE "Test unit written to [^ ]+" "$log" | tail -1 | sed 's/Test unit written to //' || true)
    result="CRASHED (exit $rc) ${artifact:+input: $artifact} log: $log"
  fi
  printf '%-12s %12s %8s %7s %7s  %s\n' "$t" "${execs:--}" "${rate:--}" "${cov:--}" "${ft:--}" "$result"
done
if [ "$crashed" -ne 0 ]; then
  echo "fuzz.sh: at least one target crashed; reproduce with $build/tests/fuzz/fuzz_<target> <input>" >&2
  exit 1
fi
