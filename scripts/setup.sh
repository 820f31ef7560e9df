#!/usr/bin/env bash
# Idempotent set-up: installs the Debian packages toonwater needs (only those missing),
# then configures and builds the project into ./build (or $TOONWATER_BUILD_DIR).
# --tests (scripts/test.sh) also installs test_packages, which only some tests need, so that
# the main job's set-up (scripts/demo.sh) stays as fast as it is.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${TOONWATER_BUILD_DIR:-$root/build}

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libcli11-dev libtomlplusplus-dev zlib1g-dev
  libtbb-dev  # parallel loops (common/parallel.hpp)
  libopenimageio-dev openimageio-tools fonts-dejavu-core
  povray
  libopenmesh-dev
  libopenvdb-dev libboost-dev  # .vdb level sets (analyzer/readers/vdb); OpenVDB's headers include Boost
  libgtest-dev libbenchmark-dev
  clang-14 libclang-rt-14-dev  # fuzzing (scripts/fuzz.sh)
  slurm-wlm munge parallel     # render farms (render --on slurm|parallel) and their tests
)
test_packages=(
  blender python3  # the add-on's tests (tests/blender), Blender headless
  ffmpeg           # render --video and its tests (ffprobe)
)

case ${1:-} in
  --tests) packages+=("${test_packages[@]}") ;;
  "") ;;
  *) echo "setup: unknown option '$1' (--tests)" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
