#!/usr/bin/env bash
# Do light points blink? Aperture against Mesa llvmpipe (OSMesa, LP_NUM_THREADS=2) drawing the same
# lights as osgSim-based image generators do, on a slow approach to a lit runway: each light's
# energy per frame from the images, its ripple over the approach, its centroid's wobble, the time
# of a light-only frame, and a light passing behind a wall's edge (tests/bench/light_blink_bench.cc
# says what each table measures). About a minute and a half on 2 cores.
#
#   scripts/bench-lights.sh                              # 1280x720 and 1920x1080, 180 frames
#   SIZES=1280x720 FRAMES=60 scripts/bench-lights.sh     # a quick look
#   CSV=out/lights.csv PREVIEW=out/lights scripts/bench-lights.sh   # every light's every frame,
#                                                        # and Aperture's first frame as PNG
#
# OSMesa (Debian's libosmesa6-dev) is a benchmark dependency, not a product one: installed here
# when missing, then the build is configured (or reconfigured) so that the target exists.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! dpkg-query -W -f='${Status}' libosmesa6-dev 2>/dev/null | grep -q "install ok installed"; then
  echo "bench-lights: installing libosmesa6-dev (benchmark dependency)"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends libosmesa6-dev \
    || { $sudo apt-get update -q && DEBIAN_FRONTEND=noninteractive \
         $sudo apt-get install -y -q --no-install-recommends libosmesa6-dev; }
fi
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE="${APERTURE_BUILD_TYPE:-Release}" >/dev/null
else
  cmake build >/dev/null   # picks up OSMesa if it was just installed
fi
cmake --build build -j "$(nproc)" --target light_blink_bench >/dev/null
args=(--frames "${FRAMES:-180}" --sizes "${SIZES:-1280x720,1920x1080}" --aa "${AA:-box2,box1,tent2}"
      --peer_min_sizes "${PEER_MIN_SIZES:-1.5,0}" --time_every "${TIME_EVERY:-6}"
      --edge_frames "${EDGE_FRAMES:-120}" --edge_step "${EDGE_STEP:-0.025}")
if [ -n "${CSV:-}" ]; then args+=(--csv "$CSV"); fi
if [ -n "${PREVIEW:-}" ]; then args+=(--preview "$PREVIEW"); fi
LP_NUM_THREADS=2 build/tests/light_blink_bench "${args[@]}"   # progress on stderr, tables on stdout
