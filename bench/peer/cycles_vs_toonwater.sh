#!/usr/bin/env bash
# toonwater against Blender Cycles' toon render of the same frames (issue 35): the violent
# Mantaflow dam break (../shared/data/mantaflow-dambreak) at 640×360, the same camera, rendered
# by toonwater (povgen + render, the default look) and by Blender Cycles (4 samples, a colour
# ramp on the light angle, Freestyle outlines: cycles_toon.py), whole processes timed in turn,
# A B A B ..., after one warm-up of each. Prints each side's median, min and max wall time, the
# median of the pairs' ratios toonwater / Cycles, and a one-line summary.
#   bench/peer/cycles_vs_toonwater.sh [FRAMES] [RUNS] [LOOK]     (default 14-22 5 opaque)
#   bench/peer/cycles_vs_toonwater.sh --one toonwater|cycles [FRAMES] [LOOK]   one run, not timed
# LOOK is the Cycles water's: opaque (issue 35's peer) or see-through (the free surface
# transmits toonwater's share, 0.4 by default, as toonwater's does).
# Environment: TOONWATER (build/cli/toonwater), BLENDER (blender), DATA (the bake), OUT
# (out/peer). Frames: OUT/toonwater/frame_NN.png and OUT/cycles/frame_NNNN.png.
# Not timed: a first povgen into OUT/camera, whose scene.pov gives Blender the camera, sun,
# colours and band limits (cycles_toon.py reads it; a user would set them up once by hand).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
TOONWATER=${TOONWATER:-$root/build/cli/toonwater}
BLENDER=${BLENDER:-blender}
DATA=${DATA:-$root/../shared/data/mantaflow-dambreak}
OUT=${OUT:-out/peer}
WIDTH=640
HEIGHT=360

fail() { echo "cycles_vs_toonwater: error: $*" >&2; exit 1; }

one=
if [[ ${1:-} == --one ]]; then
  one=${2:?--one needs toonwater or cycles}
  [[ $one == toonwater || $one == cycles ]] || fail "--one takes toonwater or cycles, not '$one'"
  shift 2
fi
FRAMES=${1:-14-22}
if [[ -n $one ]]; then RUNS=1 LOOK=${2:-opaque}; else RUNS=${2:-5} LOOK=${3:-opaque}; fi
[[ $FRAMES =~ ^[0-9]+-[0-9]+$ ]] || fail "FRAMES is FIRST-LAST, not '$FRAMES'"
[[ $RUNS =~ ^[1-9][0-9]*$ ]] || fail "RUNS is a whole number ≥ 1, not '$RUNS'"
case $LOOK in
  opaque) see_through=() ;;
  see-through) see_through=(--see-through) ;;
  *) fail "LOOK is opaque or see-through, not '$LOOK'" ;;
esac

if [[ ! -d $DATA/cache/mesh ]]; then
  echo "cycles_vs_toonwater: skipped: $DATA/cache/mesh not found (the shared Mantaflow bake" \
       "is not part of the repository; set DATA)" >&2
  exit 0
fi
[[ -x $TOONWATER ]] || fail "$TOONWATER: not found or not executable (build first, or set TOONWATER)"
command -v "$BLENDER" >/dev/null || fail "$BLENDER: not found (scripts/setup.sh --tests installs it)"
mkdir -p "$OUT" || fail "$OUT: cannot create the output directory"

water="$DATA/cache/mesh/fluid_mesh_####.bobj.gz"
object="$DATA/sphere_####.obj"
# Mantaflow's normalised cache to world metres: the domain's longest side and centre
placement=(--scale 1.2 --translate 0,0,0.3)

povgen() {  # povgen DIR: the default look of FRAMES at WIDTH×HEIGHT
  "$TOONWATER" povgen --water "$water" "${placement[@]}" --up z --object "$object" \
    --set render.width=$WIDTH --set render.height=$HEIGHT --set render.frames=$FRAMES \
    --out "$1"
}

toonwater_run() {
  povgen "$OUT/toonwater" && "$TOONWATER" render "$OUT/toonwater"
}

cycles_run() {
  "$BLENDER" -b --factory-startup --python-exit-code 1 --python "$here/cycles_toon.py" -- \
    --scene "$OUT/camera" --water "$water" "${placement[@]}" \
    --object "$object" --frames "$FRAMES" "${see_through[@]}" --out "$OUT/cycles"
}

# run LOG COMMAND...: the command's output into LOG; on failure its last lines and exit 1
run() {
  local log=$1 status=0; shift
  "$@" >"$log" 2>&1 || status=$?
  if ((status != 0)); then
    tail -n 5 "$log" >&2
    fail "$* failed (exit $status; log $log)"
  fi
}

if [[ ! -f $OUT/camera/scene.pov ]] || [[ $(cat "$OUT/camera/.frames" 2>/dev/null) != "$FRAMES" ]]; then
  run "$OUT/camera.log" povgen "$OUT/camera"
  echo "$FRAMES" >"$OUT/camera/.frames"
fi

if [[ -n $one ]]; then
  run "$OUT/$one.log" "${one}_run"
  exit 0
fi

now() { date +%s.%N; }
minus() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a - b }'; }
divide() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a / b }'; }
list() { printf '%s\n' "$@"; }
# summary [--median]: median (min–max) of the numbers on standard input, or the median alone
summary() {
  sort -g | awk -v only="${1:-}" '{ v[NR] = $1 } END {
    m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
    if (only != "") printf "%.2f", m; else printf "%.2f (%.2f–%.2f)", m, v[1], v[NR] }'
}

echo "cycles_vs_toonwater: frames $FRAMES at ${WIDTH}×$HEIGHT, Cycles $LOOK, $RUNS runs each" \
     "after a warm-up, $(nproc) cores" >&2
run "$OUT/toonwater.log" toonwater_run
run "$OUT/cycles.log" cycles_run
tw_times=() pov_times=() render_times=() cy_times=() ratios=()
for ((i = 1; i <= RUNS; i++)); do
  t0=$(now)
  run "$OUT/toonwater.log" povgen "$OUT/toonwater"
  t1=$(now)
  run "$OUT/toonwater-render.log" "$TOONWATER" render "$OUT/toonwater"
  t2=$(now)
  run "$OUT/cycles.log" cycles_run
  t3=$(now)
  pov_times+=("$(minus "$t1" "$t0")") render_times+=("$(minus "$t2" "$t1")")
  tw_times+=("$(minus "$t2" "$t0")") cy_times+=("$(minus "$t3" "$t2")")
  ratios+=("$(divide "${tw_times[-1]}" "${cy_times[-1]}")")
  echo "run $i: toonwater ${tw_times[-1]} s (povgen ${pov_times[-1]}, render ${render_times[-1]})," \
       "Cycles ${cy_times[-1]} s, ratio ${ratios[-1]}" >&2
done

echo "| whole process, wall seconds | median (min–max) |"
echo "|---|---|"
echo "| toonwater (povgen + render) | $(list "${tw_times[@]}" | summary) |"
echo "| toonwater povgen | $(list "${pov_times[@]}" | summary) |"
echo "| toonwater render | $(list "${render_times[@]}" | summary) |"
echo "| Blender Cycles toon ($LOOK) | $(list "${cy_times[@]}" | summary) |"
echo "| ratio toonwater / Cycles, pair by pair | $(list "${ratios[@]}" | summary) |"
echo "cycles_vs_toonwater: toonwater $(list "${tw_times[@]}" | summary --median) s," \
     "Cycles $(list "${cy_times[@]}" | summary --median) s," \
     "ratio $(list "${ratios[@]}" | summary --median) (medians of $RUNS alternating runs," \
     "frames $FRAMES, ${WIDTH}x$HEIGHT, Cycles $LOOK)"
