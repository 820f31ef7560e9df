#!/usr/bin/env bash
# Flicker of the flow regions in rendered frames, with and without temporal coherence:
# the share of water pixels whose flow colour (ridge, valley, none) changes between
# consecutive frames, averaged over the sequence. Defaults to ../shared/data/mantaflow-wake.
#   scripts/measure_flicker.sh [WATER_PATTERN] [UP_AXIS]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
toonwater=${TOONWATER:-$root/build/cli/toonwater}
pattern=${1:-$root/../shared/data/mantaflow-wake/water_####.obj}
up=${2:-z}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Per pixel: 2 ridge (magenta), 1 valley (green), 0 other water, and background pixels left out.
classify() {
  oiiotool --dumpdata "$1" | awk 'NR > 1 {
    r = $3; g = $4; b = $5
    if (r > 200 && g < 60 && b > 200) c = 2; else if (g > 200 && r < 60 && b < 60) c = 1;
    else if (r > 250 && g > 250 && b > 250) c = -1; else c = 0
    print c }'
}

measure() {  # measure NAME COHERENCE
  local dir=$work/coherence-$2
  "$toonwater" povgen --water "$pattern" --up "$up" --out "$dir" \
    --set flow.coherence="$2" --set 'flow.ridge_color=[1,0,1]' --set 'flow.valley_color=[0,1,0]' \
    --set water.transmit=0 --set water.reflection=0 --set water.ks=0 --set outline.enabled=false \
    --set render.antialias=false --set 'render.background=[1,1,1]' \
    --set render.width=240 --set render.height=135 >/dev/null 2>&1
  (cd "$dir" && povray scene.ini -D >/dev/null 2>&1)
  local previous="" changed=0 water=0
  for frame in $(find "$dir" -name 'frame_*.png' | sort -V); do
    classify "$frame" > "$frame.classes"
    if [ -n "$previous" ]; then
      read -r c w < <(paste "$previous" "$frame.classes" |
        awk '$1 >= 0 && $2 >= 0 { w++; if ($1 != $2) c++ } END { print c + 0, w + 0 }')
      changed=$((changed + c)); water=$((water + w))
    fi
    previous=$frame.classes
  done
  awk -v c="$changed" -v w="$water" -v n="$1" 'BEGIN { printf "%s: %.2f %% of water pixels change flow colour per frame\n", n, 100 * c / w }'
}

measure "without coherence" false
measure "with coherence" true
