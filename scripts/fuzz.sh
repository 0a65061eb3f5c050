#!/usr/bin/env bash
# Runs every libFuzzer harness (fuzz/fuzz_*.cpp) for SECONDS each (default 300), CAMSIM_JOBS
# of them at a time.
#   scripts/fuzz.sh [SECONDS] [HARNESS...]
# Builds them first in $CAMSIM_FUZZ_BUILD_DIR (default build-fuzz/; Clang, CAMSIM_FUZZ=ON;
# scripts/test.sh passes its build-asan/).
# Exits non-zero if any harness finds a crash, a sanitizer error, a leak, a timeout or an
# out-of-memory; the input is then in <build>/fuzz/artifacts/<harness>/ (replay it with
# `<build>/fuzz/fuzz_<harness> FILE`). The seed corpora in fuzz/corpus/ are only read: new
# inputs go to <build>/fuzz/work/<harness>/ (copy good ones into fuzz/corpus/ by hand, and
# any input that once failed into fuzz/regressions/<harness>/).
# Environment: CAMSIM_JOBS (parallel build jobs and harnesses at a time, default: nproc).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-300}
shift || true
build_dir=${CAMSIM_FUZZ_BUILD_DIR:-build-fuzz}
jobs=${CAMSIM_JOBS:-$(nproc)}
harnesses=("$@")
if ((${#harnesses[@]} == 0)); then  # all: fuzz/fuzz_<harness>.cpp
  for f in fuzz/fuzz_*.cpp; do
    f=${f#fuzz/fuzz_}
    harnesses+=("${f%.cpp}")
  done
fi

# A build directory already configured with CAMSIM_FUZZ=ON keeps its configuration (the gate's
# build-asan/, which also builds the tests: scripts/test.sh); any other is configured here.
if ! grep -qs '^CAMSIM_FUZZ:BOOL=ON$' "$build_dir/CMakeCache.txt"; then
  CC=clang CXX=clang++ cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCAMSIM_FUZZ=ON -DCAMSIM_BUILD_TESTS=OFF -DCAMSIM_BUILD_BENCH=OFF \
    -DCAMSIM_WERROR=OFF -DCAMSIM_UNITY_BUILD=ON >/dev/null  # warnings: the gate's builds gate them
fi
cmake --build "$build_dir" -j"$jobs" --target "${harnesses[@]/#/fuzz_}"

# Memory: ASan's hard_rss_limit_mb, not libFuzzer's -rss_limit_mb, whose report prints a
# heap profile that takes many minutes on a heap of millions of small blocks (the
# yaml-cpp LoadAll loop, docs/testing.md); -malloc_limit_mb catches single huge requests.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:hard_rss_limit_mb=2048}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

# One harness: its log in <build>/fuzz/<harness>.log; <harness>.failed marks a finding.
fuzz_one() {
  local h=$1
  local work="$build_dir/fuzz/work/$h" artifacts="$build_dir/fuzz/artifacts/$h"
  local log="$build_dir/fuzz/$h.log"
  mkdir -p "$work" "$artifacts"
  rm -f "$build_dir/fuzz/$h.failed"
  local dict=()
  if [ -f "fuzz/dict/$h.dict" ]; then dict=(-dict="fuzz/dict/$h.dict"); fi
  local regressions=()
  if [ -d "fuzz/regressions/$h" ]; then regressions=("fuzz/regressions/$h"); fi
  echo "fuzz: $h for ${seconds}s (log: $log)" >&2
  # -timeout: one input taking > 10 s is a finding (a hang); so is > 2 GB of memory.
  # Inputs are at most 64 KiB: enough for every format, small enough to stay fast.
  if "$build_dir/fuzz/fuzz_$h" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=0 \
       -malloc_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
       -artifact_prefix="$artifacts/" "${dict[@]}" \
       "$work" "fuzz/corpus/$h" "${regressions[@]}" >"$log" 2>&1; then
    local runs
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    echo "fuzz: $h: ${runs:-?} executions, no crash" >&2
  else
    echo "fuzz: $h FAILED; last lines of $log:" >&2
    tail -n 40 "$log" >&2
    touch "$build_dir/fuzz/$h.failed"
  fi
}

# The harnesses run $jobs at a time (each is one process on one core).
running=0
for h in "${harnesses[@]}"; do
  if ((running >= jobs)); then
    wait -n || true
    running=$((running - 1))
  fi
  fuzz_one "$h" &
  running=$((running + 1))
done
wait
failed=()
for h in "${harnesses[@]}"; do
  if [ -f "$build_dir/fuzz/$h.failed" ]; then failed+=("$h"); fi
done
if ((${#failed[@]})); then
  echo "fuzz: findings in: ${failed[*]} (inputs in $build_dir/fuzz/artifacts/)" >&2
  exit 1
fi
