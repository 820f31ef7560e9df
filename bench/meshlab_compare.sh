#!/usr/bin/env bash
# Whole-process `toonwater analyze --up z` against MeshLab's Discrete Curvatures filter
# (meshlabserver, Debian's 2020.09, under one Xvfb server started beforehand so that its own
# start-up is not counted), and optionally against a second toonwater build, on the
# bench_analyzer height field z = 0.1 sin 6x cos 6y over [-1, 1]^2 written as a binary PLY of
# float coordinates at 235^2 (55k) and 1000^2 (1M) vertices. Runs alternate (MeshLab, A, B) in
# each of PAIRS rounds, each round starting one program later (bench/alternate.py --rotate: run
# just after MeshLab, a build took 20-40 ms more at 55k than the same build run after the
# other); prints the medians of wall and CPU (user + system) time and of the rounds' ratios to
# MeshLab. Neither program writes an output.
#
# Usage: bench/meshlab_compare.sh TOONWATER [OTHER_TOONWATER] [PAIRS]   (PAIRS default 7)
# Needs: meshlab and xvfb (apt-get install meshlab xvfb), python3.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
a=$1
b=${2:-}
pairs=${3:-7}
work=$(mktemp -d)
trap 'rm -rf "$work"; [ -n "${xvfb_pid:-}" ] && kill "$xvfb_pid" 2>/dev/null || true' EXIT

python3 - "$work" <<'PY'
import math, struct, sys
from array import array
for n, name in ((235, "55k"), (1000, "1M")):
    axis = [-1 + 2 * i / (n - 1) for i in range(n)]
    vertices = array("f")
    for x in axis:  # vertex i * n + j at (axis[i], axis[j])
        for y in axis:
            vertices.extend((x, y, 0.1 * math.sin(6 * x) * math.cos(6 * y)))
    face = struct.Struct("<Biii")
    faces = []
    for i in range(n - 1):
        for j in range(n - 1):
            v = i * n + j
            faces.append(face.pack(3, v, v + n, v + n + 1))
            faces.append(face.pack(3, v, v + n + 1, v + 1))
    with open(f"{sys.argv[1]}/{name}.ply", "wb") as f:
        f.write((f"ply\nformat binary_little_endian 1.0\nelement vertex {n * n}\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 f"element face {len(faces)}\nproperty list uchar int vertex_indices\n"
                 "end_header\n").encode())
        f.write(vertices.tobytes())
        f.write(b"".join(faces))
PY

filter() {
  printf ' <filter name="Discrete Curvatures">\n  <Param type="RichEnum" value="%s" name="CurvatureType" enum_val0="Mean Curvature" enum_val1="Gaussian Curvature" enum_val2="RMS Curvature" enum_val3="ABS Curvature" enum_cardinality="4" description="Type:" tooltip=""/>\n </filter>\n' "$1"
}
{ echo '<!DOCTYPE FilterScript><FilterScript>'; filter 1; echo '</FilterScript>'; } >"$work/gaussian.mlx"
{ echo '<!DOCTYPE FilterScript><FilterScript>'; filter 1; filter 0; echo '</FilterScript>'; } >"$work/gaussian_mean.mlx"

if [ -z "${DISPLAY:-}" ]; then
  Xvfb :99 -nolisten tcp >/dev/null 2>&1 &
  xvfb_pid=$!
  export DISPLAY=:99
  sleep 2
fi

analyze() { printf '%q analyze --up z %q' "$1" "$work/$size.ply"; }  # as shell text

for size in 55k 1M; do
  script=$work/gaussian_mean.mlx
  meshlab_name="Gaussian + mean"
  [ "$size" = 1M ] && script=$work/gaussian.mlx meshlab_name=Gaussian
  echo "$size vertices, MeshLab's $meshlab_name:"
  "$here/alternate.py" --rounds "$pairs" --rotate \
    "MeshLab=$(printf 'meshlabserver -i %q -s %q' "$work/$size.ply" "$script")" \
    "toonwater A=$(analyze "$a")" ${b:+"toonwater B=$(analyze "$b")"}
done
