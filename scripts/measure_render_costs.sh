#!/usr/bin/env bash
# POV-Ray's cost of a scene change, and whether it leaves the picture as it was: two scene
# directories written by `toonwater povgen` (A, the reference, and B, the candidate) rendered
# over the same frames, every pixel of B compared with A's (the largest channel difference, and
# how many pixels differ by more than 8/255), then A and B timed in turn, A B A B ..., one
# POV-Ray thread each, with the medians of user CPU and wall seconds and of the rounds' ratios.
#   scripts/measure_render_costs.sh SCENE_A SCENE_B [FIRST_FRAME LAST_FRAME] [ROUNDS]
# Needs povray, idiff (openimageio-tools) and GNU time; writes only into a temporary directory.
set -euo pipefail
if [ $# -lt 2 ]; then
  sed -n '2,8p' "$0" >&2
  exit 2
fi
a=$(cd "$1" && pwd)
b=$(cd "$2" && pwd)
first=${3:-}
last=${4:-$first}
rounds=${5:-5}
frames=()
[ -n "$first" ] && frames=(+SF"$first" +EF"$last")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

render() {  # render SCENE OUT_PREFIX: one POV-Ray thread, prints "user wall" seconds
  (cd "$1" && /usr/bin/time -f "%U %e" -o "$work/time" \
    povray scene.ini -D +WT1 "${frames[@]}" +O"$2" >/dev/null 2>&1)
  cat "$work/time"
}

mkdir -p "$work/a" "$work/b"
render "$a" "$work/a/frame_" >/dev/null
render "$b" "$work/b/frame_" >/dev/null
for image in "$work"/a/*.png; do
  name=$(basename "$image")
  # idiff's status says whether the images differ: reported below, not a failure of this script.
  { idiff -fail 0.0333 -warn 0.0333 "$image" "$work/b/$name" 2>&1 || true; } |
    awk -v name="$name" '/Max error/ { max = $4 } / over / { over = $1 }
      END { printf "%s: largest difference %d/255, %d pixels above 8/255\n", name, max * 255 + 0.5, over }'
done

for round in $(seq "$rounds"); do
  read -r ua wa < <(render "$a" "$work/a/frame_")
  read -r ub wb < <(render "$b" "$work/b/frame_")
  echo "$ua $wa $ub $wb"
done | awk '
  { ua[NR] = $1; wa[NR] = $2; ub[NR] = $3; wb[NR] = $4; r[NR] = ($1 > 0 ? $3 / $1 : 0) }
  function median(v, n,   i, j, t) {
    for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (v[j] < v[i]) { t = v[i]; v[i] = v[j]; v[j] = t }
    return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
  }
  END {
    n = NR
    printf "%d rounds, medians: A user %.2f s wall %.2f s, B user %.2f s wall %.2f s, B/A user %.3f\n",
      n, median(ua, n), median(wa, n), median(ub, n), median(wb, n), median(r, n)
  }'
