#!/usr/bin/env bash
# The main job, end to end on a fresh machine: set-up and build, then a cartoon water animation
# made from nothing but toonwater itself —
#   simulate   the wake example: a sphere crossing open water (toonwater simulate wake)
#   analyze    curvature and flow regions of the middle frame (CSV, PLY)
#   povgen     POV-Ray scenes with the Cartoon Water Shader (examples/wake/scene.toml), and
#              curvature maps of every frame on one shared colour range
#   render     the frames with POV-Ray, ranges of frames in several processes a core
#   preview    an animated GIF of the frames (OpenImageIO's oiiotool)
# Usage: scripts/demo.sh [OUT_DIR]            (default: ./out, git-ignored)
# Environment: TOONWATER_FRAMES (24), TOONWATER_WIDTH (480), TOONWATER_HEIGHT (270),
#              TOONWATER_BUILD_DIR (./build), TOONWATER_SKIP_SETUP=1 to use an existing build.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=$(mkdir -p "${1:-$root/out}" && cd "${1:-$root/out}" && pwd)
frames=${TOONWATER_FRAMES:-24}
width=${TOONWATER_WIDTH:-480}
height=${TOONWATER_HEIGHT:-270}
build_dir=${TOONWATER_BUILD_DIR:-$root/build}

start=$SECONDS
step() { printf '\n== [%s/6] %s  (%d s so far)\n' "$1" "$2" $((SECONDS - start)) >&2; }

step 1 "set-up and build (scripts/setup.sh)"
if [ "${TOONWATER_SKIP_SETUP:-0}" != 1 ]; then "$root/scripts/setup.sh"; fi
tw="$build_dir/cli/toonwater"
[ -x "$tw" ] || { echo "demo: $tw was not built" >&2; exit 1; }

demo="$out/wake"
rm -rf "$demo"  # only this demo's own outputs: a shorter re-run leaves no stale frames
mkdir -p "$demo/analysis"

step 2 "simulate the wake example: $frames frames"
"$tw" simulate wake --frames "$frames" --out "$demo/sim"

step 3 "analyze: curvature and flow regions of the middle frame"
middle=$(printf 'water_%04d' $(((frames + 1) / 2)))
"$tw" analyze "$demo/sim/$middle.obj" --csv "$demo/analysis/$middle.csv" \
  --ply "$demo/analysis/$middle.ply"

step 4 "povgen: POV-Ray scenes at ${width}x${height}, curvature maps"
cp "$root/examples/wake/scene.toml" "$demo/scene.toml"  # its mesh paths are relative to it
"$tw" povgen --config "$demo/scene.toml" --water "$demo/sim/water_####.obj" \
  --set "render.width=$width" --set "render.height=$height" --out "$demo/scene" \
  --maps "$demo/maps"

step 5 "render with POV-Ray (ranges of frames, four processes a core)"
"$tw" render "$demo/scene"

step 6 "animated preview"
oiiotool "$demo"/scene/frame_*.png --siappendall --attrib:type=rational FramesPerSecond 12/1 \
  -o "$demo/wake.gif"

cat >&2 <<DONE

demo: done in $((SECONDS - start)) s. Results in $demo:
  animation   $demo/wake.gif
  frames      $demo/scene/frame_*.png   (POV-Ray scenes beside them: cd $demo/scene && povray scene.ini)
  simulation  $demo/sim/water_*.obj, sphere_*.obj   (y up)
  curvature   $demo/analysis/$middle.csv, $middle.ply
  maps        $demo/maps/   (EXR with height, K, H, k1, k2, label; PNG previews)
DONE
