#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan) and runs each for a bounded time on its seed
# corpus (tests/fuzz/corpus/<target>: meshes and configurations the tests read too) and on the
# inputs that were once findings (tests/fuzz/regressions/<target>). Fails when any target finds
# a crash, a sanitizer report, a leak, an allocation over the limit or an input that takes longer
# than the per-input timeout; the input is kept in the build directory's artifacts/ and the
# command to reproduce it printed.
#
#   scripts/fuzz.sh [TARGET...]          default: every target
#   FUZZ_SECONDS=60                      time per target
#   FUZZ_PARALLEL=$(nproc)               targets run at the same time
#   FUZZ_BUILD_DIR=build-fuzz            its own build directory (instrumented)
#
# New inputs a run discovers go to FUZZ_BUILD_DIR/corpus/<target>, never into the repository.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${FUZZ_BUILD_DIR:-$root/build-fuzz}
seconds=${FUZZ_SECONDS:-60}
parallel=${FUZZ_PARALLEL:-$(nproc)}
all_targets=(obj off ply stl vtk bobj flip_bobj wwp analyze config)
targets=("${@:-${all_targets[@]}}")

build() {
  cmake -S "$root" -B "$build_dir" -DTOONWATER_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++-14 \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTOONWATER_BUILD_TESTS=OFF \
    -DTOONWATER_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build "$build_dir" -j "$(nproc)" --target "${targets[@]/#/fuzz_}"
}

# run_target NAME: one bounded libFuzzer run; its log is FUZZ_BUILD_DIR/logs/NAME.log.
run_target() {
  local name=$1 dict=()
  local seeds=$root/tests/fuzz/corpus/$name regressions=()
  [ -d "$root/tests/fuzz/regressions/$name" ] && regressions=("$root/tests/fuzz/regressions/$name")
  local dict_file=$root/tests/fuzz/${name/analyze/obj}.dict
  [ -f "$dict_file" ] && dict=(-dict="$dict_file")
  mkdir -p "$build_dir/corpus/$name" "$build_dir/artifacts"
  # -timeout: an input running longer is a hang; -malloc_limit_mb: a single allocation over it
  # (e.g. from a count in a header nobody checked) is a finding, as is a leak at the end.
  "$build_dir/tests/fuzz/fuzz_$name" "$build_dir/corpus/$name" "$seeds" "${regressions[@]}" \
    "${dict[@]}" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=512 \
    -max_len=8192 -print_final_stats=1 -artifact_prefix="$build_dir/artifacts/$name-" \
    >"$build_dir/logs/$name.log" 2>&1
}

report() {
  local name=$1 status=$2 runs
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$build_dir/logs/$name.log" | tail -1)
  if [ "$status" -eq 0 ]; then
    printf 'fuzz: %-8s %12s executions, no finding\n' "$name" "${runs:-?}"
  else
    printf 'fuzz: %-8s FAILED (exit %s) after %s executions; log: %s\n' "$name" "$status" \
      "${runs:-?}" "$build_dir/logs/$name.log"
    grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error|artifact_prefix|Test unit written)' \
      "$build_dir/logs/$name.log" | head -5 || true
  fi
}

build
mkdir -p "$build_dir/logs"
failed=0
for ((i = 0; i < ${#targets[@]}; i += parallel)); do
  batch=("${targets[@]:i:parallel}")
  pids=()
  for name in "${batch[@]}"; do
    run_target "$name" &
    pids+=($!)
  done
  for j in "${!batch[@]}"; do
    status=0
    wait "${pids[j]}" || status=$?
    report "${batch[j]}" "$status"
    [ "$status" -eq 0 ] || failed=1
  done
done
if [ "$failed" -ne 0 ]; then
  echo "fuzz: findings above; reproduce with $build_dir/tests/fuzz/fuzz_NAME ARTIFACT" >&2
  exit 1
fi
