#!/usr/bin/env bash
# Installs every package the gates use and builds everything (scripts/setup.sh --test:
# scripts/packages/render.txt and test.txt), then runs every quality gate (docs/testing.md):
#   1. the test suite (CTest) on the Release build in build/ (the SIMD path, CAMSIM_SIMD=ON),
#      with the Python module's pytest suite (CTest label python, docs/python.md);
#      then every tracked .cpp/.h is checked to be clang-formatted (scripts/format.sh
#      --check, a few seconds);
#      then `camsim dataset` on a real single-node Slurm cluster started from Debian's
#      slurm-wlm and munge (tests/cluster/slurm_dataset_test.sh, about a minute; needs root:
#      it fails, saying why, where the daemons cannot start);
#   2. the same suite and the libFuzzer harnesses in one instrumented build (Clang,
#      CAMSIM_SANITIZE=ON and CAMSIM_FUZZ=ON: AddressSanitizer + UndefinedBehaviorSanitizer,
#      libFuzzer's coverage instrumentation; -O1 -g1: line tables for the reports) in
#      build-asan/: the suite less the slow tests of tests/asan_skip.txt, and every fuzz seed
#      and regression input replayed once (CTest label fuzz); built portable
#      (CAMSIM_SIMD=OFF: sensor/base/simd.h's portable path, no AVX2 copy, no x86 flag), so
#      the whole suite runs on both paths without a build stage of its own; the libraries
#      and tests unity-built (CAMSIM_UNITY_BUILD: a few large translation units, half the
#      compiling; as setup.sh builds the Release stage and README's first command); Clang's
#      warnings are errors too (the Release stage gates GCC's);
#   3. each harness of that build fuzzed for CAMSIM_FUZZ_SECONDS (default 12) by
#      scripts/fuzz.sh.
# Every stage runs even when an earlier one failed; the script fails if any did. Each stage
# prints its wall time, and its build and test parts separately (docs/testing.md's table).
# Environment: CAMSIM_BUILD_DIR, CAMSIM_ASAN_BUILD_DIR (build directories),
# CAMSIM_FUZZ_SECONDS (0 skips the fuzzing runs, not the replay), CAMSIM_JOBS (parallel
# build and test jobs, default: nproc).
set -uo pipefail
cd "$(dirname "$0")/.."

build_dir=${CAMSIM_BUILD_DIR:-build}
asan_dir=${CAMSIM_ASAN_BUILD_DIR:-build-asan}
fuzz_seconds=${CAMSIM_FUZZ_SECONDS:-12}
jobs=${CAMSIM_JOBS:-$(nproc)}
failed=()
start=$SECONDS

stage() {  # stage NAME COMMAND...: runs COMMAND, records NAME if it fails
  local name=$1
  shift
  local t0=$SECONDS
  echo "== test.sh: $name" >&2
  if "$@"; then
    echo "== test.sh: $name: ok ($((SECONDS - t0)) s)" >&2
  else
    echo "== test.sh: $name: FAILED ($((SECONDS - t0)) s)" >&2
    failed+=("$name")
  fi
}

part() {  # part NAME COMMAND...: runs COMMAND and prints its wall time
  local name=$1 t0=$SECONDS rc=0
  shift
  "$@" || rc=$?
  echo "== test.sh:   $name: $((SECONDS - t0)) s" >&2
  return "$rc"
}

release_suite() {
  CAMSIM_BUILD_DIR=$build_dir scripts/setup.sh --test &&
    part "Release suite" ctest --test-dir "$build_dir" --output-on-failure -j"$jobs"
}

# The instrumented build has no Python module (-DCAMSIM_PYTHON=OFF): an ASan-instrumented
# extension cannot be imported into Debian's unsanitised python3 (the ASan runtime must be
# loaded first), so the pytest suite runs in the Release stage only. Every sanitizer report
# aborts the test (-fno-sanitize-recover=all) and LeakSanitizer fails a process that leaks.
# The slow rendered and statistical tests listed in tests/asan_skip.txt, each with its reason
# and the cheaper tests that run its code under the sanitizers, are left out there (they run
# in the Release suite). One Clang build serves the suite and the fuzzing: the libraries are
# compiled once instead of twice (docs/testing.md, "Trimmed again (2026-12-07)").
# A parameterised test's CTest name goes on with "  # GetParam() = ...": hence ( |$).
asan_skip_regex() {  # ^(A\.B|C\.D|...)( |$) from the first word of each line of tests/asan_skip.txt
  local names
  names=$(sed -e 's/#.*//' -e '/^[[:space:]]*$/d' tests/asan_skip.txt | awk '{print $1}' |
    sed 's/[.]/\\./g' | paste -sd '|')
  printf '^(%s)( |$)' "$names"
}

asan_suite() {
  local asan=detect_leaks=1:strict_init_order=1:detect_stack_use_after_return=1
  local slow
  slow=$(asan_skip_regex)
  CC=clang CXX=clang++ cmake -S . -B "$asan_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCAMSIM_SANITIZE=ON -DCAMSIM_FUZZ=ON \
    -DCAMSIM_SIMD=OFF -DCAMSIM_BUILD_BENCH=OFF -DCAMSIM_PYTHON=OFF -DCAMSIM_UNITY_BUILD=ON \
    >/dev/null &&
    part "ASan build" cmake --build "$asan_dir" -j"$jobs" &&
    ASAN_OPTIONS=${ASAN_OPTIONS:-$asan} \
      UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
      part "ASan suite and fuzz replay" ctest --test-dir "$asan_dir" --output-on-failure \
      -j"$jobs" -E "$slow"
}

fuzz_run() {
  CAMSIM_FUZZ_BUILD_DIR=$asan_dir CAMSIM_JOBS=$jobs scripts/fuzz.sh "$fuzz_seconds"
}

stage "Release test suite ($build_dir)" release_suite
stage "clang-format check" scripts/format.sh --check
stage "Slurm: camsim dataset on a single-node cluster" \
  tests/cluster/slurm_dataset_test.sh "$build_dir/camsim" "$build_dir/slurm-test"
stage "ASan+UBSan test suite and fuzz replay ($asan_dir)" asan_suite
if ((fuzz_seconds > 0)); then
  stage "fuzzing, ${fuzz_seconds} s per harness ($asan_dir)" fuzz_run
fi

echo "== test.sh: $((SECONDS - start)) s in all" >&2
if ((${#failed[@]})); then
  printf '== test.sh: FAILED: %s\n' "${failed[@]}" >&2
  exit 1
fi
echo "== test.sh: all passed" >&2
