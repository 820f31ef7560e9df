#!/usr/bin/env bash
# POV-Ray's cost of a scene change, and whether it leaves the picture as it was: two scene
# directories written by `toonwater povgen` (A, the reference, and B, the candidate) rendered
# over the same frames, every pixel of B compared with A's (the largest channel difference, and
# how many pixels differ by more than 8/255), then A and B timed in turn, A B A B ..., one
# POV-Ray thread each, with the medians of CPU and wall seconds and of the rounds' ratios B / A
# (bench/alternate.py).
#   scripts/measure_render_costs.sh SCENE_A SCENE_B [FIRST_FRAME LAST_FRAME] [ROUNDS]
# Needs povray, idiff (openimageio-tools) and python3; writes only into a temporary directory.
set -euo pipefail
if [ $# -lt 2 ]; then
  sed -n '2,8p' "$0" >&2
  exit 2
fi
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
a=$(cd "$1" && pwd)
b=$(cd "$2" && pwd)
first=${3:-}
last=${4:-$first}
rounds=${5:-5}
frames=()
[ -n "$first" ] && frames=(+SF"$first" +EF"$last")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

render() {  # render SCENE OUT_PREFIX, as shell text: one POV-Ray thread
  printf 'cd %q && povray scene.ini -D +WT1' "$1"
  printf ' %q' "${frames[@]}" +O"$2"
}

mkdir -p "$work/a" "$work/b"
for side in a b; do
  scene=${!side}
  bash -c "$(render "$scene" "$work/$side/frame_")" >"$work/$side.log" 2>&1 ||
    { tail -n 5 "$work/$side.log" >&2; echo "measure_render_costs: POV-Ray failed on $scene" >&2; exit 1; }
done
for image in "$work"/a/*.png; do
  name=$(basename "$image")
  # idiff's status says whether the images differ: reported below, not a failure of this script.
  { idiff -fail 0.0333 -warn 0.0333 "$image" "$work/b/$name" 2>&1 || true; } |
    awk -v name="$name" '/Max error/ { max = $4 } / over / { over = $1 }
      END { printf "%s: largest difference %d/255, %d pixels above 8/255\n", name, max * 255 + 0.5, over }'
done

python3 "$here/../bench/alternate.py" --rounds "$rounds" \
  "A=$(render "$a" "$work/a/frame_")" "B=$(render "$b" "$work/b/frame_")"
