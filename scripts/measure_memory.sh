#!/usr/bin/env bash
# Peak memory (max RSS, /usr/bin/time -v) of `toonwater analyze` and `toonwater povgen` on
# generated height-field meshes, in bytes per vertex. The meshes (binary PLY, float32) are written
# to a scratch directory and removed afterwards; nothing large is committed.
#
#   scripts/measure_memory.sh [TOONWATER] [SIDE...]    default: build/cli/toonwater 1000 3163
#   (a side of 1000 gives 1M vertices, 3163 gives 10M)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
toonwater=$(realpath "${1:-$root/build/cli/toonwater}")
shift || true
sides=("${@:-1000 3163}")
read -r -a sides <<<"${sides[*]}"
scratch=$(mktemp -d "${TMPDIR:-/tmp}/toonwater-memory.XXXXXX")
trap 'rm -rf "$scratch"' EXIT

# make_mesh SIDE FILE: SIDE x SIDE vertices, z = 0.05 sin(6x) cos(4y) over the unit square, y up.
make_mesh() {
  python3 - "$1" "$2" <<'PY'
import array, math, sys
n, path = int(sys.argv[1]), sys.argv[2]
xs = [i / (n - 1) for i in range(n)]
header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\n"
          "property float y\nproperty float z\nelement face %d\n"
          "property list uchar int vertex_indices\nend_header\n" % (n * n, 2 * (n - 1) ** 2))
with open(path, "wb") as out:
    out.write(header.encode())
    sin_x = [0.05 * math.sin(6 * x) for x in xs]
    for j in range(n):
        cy = math.cos(4 * xs[j])
        row = array.array("f")
        for i in range(n):
            row.extend((xs[i], sin_x[i] * cy, xs[j]))
        out.write(row.tobytes())
    for j in range(n - 1):
        row = bytearray()
        for i in range(n - 1):
            a = j * n + i
            row += bytes([3]) + array.array("i", (a, a + n, a + 1)).tobytes()
            row += bytes([3]) + array.array("i", (a + 1, a + n, a + n + 1)).tobytes()
        out.write(row)
PY
}

# peak_kb COMMAND...: runs it, prints its maximum resident set size in kB.
peak_kb() {
  /usr/bin/time -v "$@" 2>"$scratch/time.log" >/dev/null || { cat "$scratch/time.log" >&2; return 1; }
  sed -n 's/^[[:space:]]*Maximum resident set size (kbytes): //p' "$scratch/time.log"
}

# The program's own footprint (libraries, OpenImageIO), measured on a 10 x 10 mesh, is reported
# apart: "bytes/vertex" is (peak - base) / vertices.
make_mesh 10 "$scratch/small.ply"
base_kb=$(peak_kb "$toonwater" analyze "$scratch/small.ply")
echo "base (10 x 10 mesh): $((base_kb / 1000)) MB"
printf '%-10s %-34s %10s %14s\n' vertices command "peak MB" "bytes/vertex"
for side in "${sides[@]}"; do
  vertices=$((side * side))
  mesh=$scratch/height_$side.ply
  make_mesh "$side" "$mesh"
  file_mb=$(($(stat -c %s "$mesh") / 1000000))
  for run in "analyze" "analyze --csv" "povgen" "povgen, geometry only"; do
    rm -rf "$scratch/out" "$scratch/out.csv"
    case $run in
      "analyze") cmd=("$toonwater" analyze "$mesh") ;;
      "analyze --csv") cmd=("$toonwater" analyze "$mesh" --csv "$scratch/out.csv") ;;
      "povgen") cmd=("$toonwater" povgen --water "$mesh" --out "$scratch/out") ;;
      "povgen, geometry only") cmd=("$toonwater" povgen --water "$mesh" --out "$scratch/out" --set flow.enabled=false --set 'water.normals="mesh"') ;;
    esac
    kb=$(peak_kb "${cmd[@]}")
    printf '%-10s %-34s %10d %14d\n' "$vertices" "$run (file ${file_mb} MB)" $((kb / 1000)) $(((kb - base_kb) * 1000 / vertices))
  done
  rm -f "$mesh"
done
