#!/usr/bin/env bash
# toonwater against Blender Cycles' toon render of the same frames (issue 35): the violent
# Mantaflow dam break (../shared/data/mantaflow-dambreak) at 640×360, the same camera, rendered
# by toonwater (povgen + render, the default look) and by Blender Cycles (4 samples, a colour
# ramp on the light angle, Freestyle outlines: cycles_toon.py), whole processes timed in turn,
# A B A B ..., after one warm-up of each (bench/alternate.py). Prints each side's median, min
# and max wall and CPU time and the medians of the runs' ratios toonwater / Cycles.
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

# The commands as arrays: run here, and given to alternate.py as shell text.
povgen_command() {  # povgen_command DIR: the default look of FRAMES at WIDTH×HEIGHT
  command=("$TOONWATER" povgen --water "$water" "${placement[@]}" --up z --object "$object"
    --set render.width=$WIDTH --set render.height=$HEIGHT --set render.frames=$FRAMES
    --out "$1")
}
cycles_command=("$BLENDER" -b --factory-startup --python-exit-code 1 --python "$here/cycles_toon.py"
  -- --scene "$OUT/camera" --water "$water" "${placement[@]}"
  --object "$object" --frames "$FRAMES" "${see_through[@]}" --out "$OUT/cycles")
render_command=("$TOONWATER" render "$OUT/toonwater")
povgen_command "$OUT/toonwater"
toonwater_povgen_command=("${command[@]}")
text() { printf '%q ' "$@"; }

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
  povgen_command "$OUT/camera"
  run "$OUT/camera.log" "${command[@]}"
  echo "$FRAMES" >"$OUT/camera/.frames"
fi

if [[ $one == toonwater ]]; then
  run "$OUT/toonwater.log" "${toonwater_povgen_command[@]}"
  run "$OUT/toonwater-render.log" "${render_command[@]}"
  exit 0
elif [[ $one == cycles ]]; then
  run "$OUT/cycles.log" "${cycles_command[@]}"
  exit 0
fi

echo "cycles_vs_toonwater: frames $FRAMES at ${WIDTH}×$HEIGHT, Cycles $LOOK, $RUNS runs each" \
     "after a warm-up, $(nproc) cores"
"$here/../alternate.py" --rounds "$RUNS" --sum "toonwater (povgen + render)=povgen+render" \
  "Blender Cycles toon ($LOOK)=$(text "${cycles_command[@]}")" \
  "povgen=$(text "${toonwater_povgen_command[@]}")" "render=$(text "${render_command[@]}")"
