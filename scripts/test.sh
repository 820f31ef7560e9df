#!/usr/bin/env bash
# Set-up (idempotent), then every check CI runs, in this order:
#   tests     the normal build and the whole test suite                      (./build)
#   sanitize  the test suite but its POV-Ray renders again under ASan + UBSan (./build-asan)
#   fuzz      every libFuzzer target for FUZZ_SECONDS (default 30 here) each  (./build-fuzz)
# TOONWATER_CHECKS picks steps (default: all three), e.g. TOONWATER_CHECKS=tests for a quick run.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${TOONWATER_BUILD_DIR:-$root/build}
asan_build_dir=${TOONWATER_ASAN_BUILD_DIR:-$root/build-asan}
checks=${TOONWATER_CHECKS:-tests sanitize fuzz}

run_tests() {
  ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)"
}

# Every sanitizer report fails its test: UBSan aborts (-fno-sanitize-recover), ASan reports
# leaks at exit, and both print a stack trace. allocator_may_return_null: an allocation larger
# than any machine (a damaged file's stated size) fails with std::bad_alloc as it does outside
# ASan, so that the reader's one-line error for it is tested here too. The suppressed leaks are
# OpenVDB's own, on a truncated file (scripts/lsan-suppressions.txt says which). -O1, as the
# sanitizers' documentation advises: it compiles in about two thirds of -O2's time and keeps the
# reports' stacks whole. The tests labelled `render` (whole POV-Ray renders, their pixels,
# signals and farms around them) are built and run only in the normal build: here they took half
# of the step's time, and povgen and the render command's fault handling stay under the
# sanitizers through the other `cli` tests.
run_sanitized_tests() {
  cmake -S "$root" -B "$asan_build_dir" -DTOONWATER_SANITIZE=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" \
    -DTOONWATER_BUILD_BENCHMARKS=OFF -DTOONWATER_BUILD_RENDER_TESTS=OFF >/dev/null
  cmake --build "$asan_build_dir" -j "$(nproc)"
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1 \
    LSAN_OPTIONS=suppressions="$root/scripts/lsan-suppressions.txt" \
    UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir "$asan_build_dir" --output-on-failure -j "$(nproc)"
}

# 30 s a target keeps the whole run well under 30 minutes on 2 cores; longer runs:
# FUZZ_SECONDS=600 scripts/fuzz.sh.
run_fuzzers() {
  FUZZ_SECONDS=${FUZZ_SECONDS:-30} "$root/scripts/fuzz.sh"
}

# step NAME FUNCTION: runs one check and reports how long it took.
step() {
  local start=$SECONDS
  echo "test.sh: $1" >&2
  "$2"
  echo "test.sh: $1 passed in $((SECONDS - start)) s" >&2
}

"$root/scripts/setup.sh" --tests
for check in $checks; do
  case $check in
    tests) step "tests" run_tests ;;
    sanitize) step "tests under ASan + UBSan" run_sanitized_tests ;;
    fuzz) step "fuzzing" run_fuzzers ;;
    *) echo "test.sh: unknown check '$check' (tests, sanitize, fuzz)" >&2; exit 2 ;;
  esac
done
