#!/usr/bin/env bash
# A Mantaflow bake's level set (data/fluid_data_NNNN.vdb) against its mesh cache
# (mesh/fluid_mesh_NNNN.bobj.gz) as toonwater's input (issue #32: reading and meshing the level
# set at most 3× reading the mesh cache and analysing it), frame 15 of a dam break baked by
# Blender at resolution_max 96 (a 96 × 60 × 48 grid) with mesh_scale 1 and 2:
#   1. whole processes, `toonwater analyze FILE --up z`, the two inputs in turn (A B A B ...)
#      after one warm-up each (alternate.py): medians of the times and of the pairs' ratios;
#   2. in one process (bench_analyzer's BakeFrame): reading and analysing the mesh cache,
#      reading and meshing the level set, and reading, meshing and analysing it.
#   bench/level_set_vs_mesh_cache.sh [RUNS]      (default 9)
# Environment: TOONWATER (build/cli/toonwater), BENCH (build/bench/bench_analyzer), BLENDER
# (blender), OUT (out/level-set-bench: the bakes, made with mantaflow_bake.py when absent).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
TOONWATER=${TOONWATER:-$root/build/cli/toonwater}
BENCH=${BENCH:-$root/build/bench/bench_analyzer}
BLENDER=${BLENDER:-blender}
OUT=${OUT:-out/level-set-bench}
runs=${1:-9}
frame=0015

fail() { echo "level_set_vs_mesh_cache: error: $*" >&2; exit 1; }
[[ -x $TOONWATER ]] || fail "no toonwater at $TOONWATER (build it, or set TOONWATER)"
[[ -x $BENCH ]] || fail "no bench_analyzer at $BENCH (make bench_analyzer, or set BENCH)"
[[ $runs =~ ^[1-9][0-9]?$ ]] && ((runs >= 3)) || fail "RUNS must be 3-99 (a median of the runs), not '$runs'"

analyze() { printf '%q ' "$TOONWATER" analyze "$1" --up z; }  # as shell text

for mesh_scale in 1 2; do
  bake=$OUT/res96-mesh$mesh_scale
  cache=$bake/cache
  if [[ ! -f $cache/data/fluid_data_$frame.vdb || ! -f $cache/mesh/fluid_mesh_$frame.bobj.gz ]]; then
    mkdir -p "$bake"
    "$BLENDER" -b --factory-startup --python "$here/mantaflow_bake.py" -- \
      dambreak "$bake" 96 "$mesh_scale" 16 >"$bake/bake.log" 2>&1 ||
      fail "the bake failed: $bake/bake.log"
  fi
  level_set=$cache/data/fluid_data_$frame.vdb
  mesh_cache=$cache/mesh/fluid_mesh_$frame.bobj.gz
  echo "96 × 60 × 48, mesh_scale $mesh_scale, frame $frame, whole processes:"
  "$here/alternate.py" --rounds "$runs" "mesh cache=$(analyze "$mesh_cache")" \
    "level set=$(analyze "$level_set")"
  TOONWATER_BENCH_BAKE=$cache "$BENCH" --benchmark_filter='BakeFrame' \
    --benchmark_repetitions="$runs" --benchmark_enable_random_interleaving=true \
    --benchmark_report_aggregates_only=true 2>/dev/null | grep -E '_median'
done
