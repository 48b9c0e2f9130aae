#!/usr/bin/env bash
# The peer benchmark: Mesa llvmpipe (OSMesa, LP_NUM_THREADS=2) against Aperture
# (--threads 2) at 1920x1080, interleaved rounds, medians and ratios, edge PSNR against dense box
# references (tests/bench/peer_bench.cc says what each row measures).
#
#   scripts/bench-peers.sh                       # tris-10k and tris-100k, planes at 5, 20, 60 deg
#   ROUNDS=7 TRIS=10000,100000,1000000 scripts/bench-peers.sh
#   PLANES=5 TRIS=10000 scripts/bench-peers.sh
#   FILTER_YAWS=0,15,30,45,60,90 PLANES= TRIS= scripts/bench-peers.sh   # filter quality only
#   FILTER_YAWS=0,45 FILTER_TEXTURES=checker,asphalt_torcs_1024 FILTER_PITCH=5 PLANES= TRIS= \
#     scripts/bench-peers.sh                       # ... on the photos of ../shared/data/raster too
#   FILTER_YAWS=0,15,30,45,60,90 FILTER_PITCH=3,5,12,20,60 POSITIONS=4 PLANES= TRIS= \
#     scripts/bench-peers.sh                       # ... every pitch, four camera positions pooled
#                                                  # (references cached with aperture-bench filter's, CACHE)
#   FLICKER_FRAMES=120 PLANES= TRIS= scripts/bench-peers.sh              # flicker with llvmpipe
#   MEMORY=100000,1000000 PLANES= TRIS= scripts/bench-peers.sh          # peak memory of a frame
#
# OSMesa (Debian's libosmesa6-dev) is a benchmark dependency, not a product one: installed here
# when missing, then the build is reconfigured so that the peer_bench target exists.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! dpkg-query -W -f='${Status}' libosmesa6-dev 2>/dev/null | grep -q "install ok installed"; then
  echo "bench-peers: installing libosmesa6-dev (benchmark dependency)"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends libosmesa6-dev \
    || { $sudo apt-get update -q && DEBIAN_FRONTEND=noninteractive \
         $sudo apt-get install -y -q --no-install-recommends libosmesa6-dev; }
fi
scripts/build.sh >/dev/null
cmake build >/dev/null   # picks up OSMesa if it was just installed
cmake --build build -j "$(nproc)" --target peer_bench >/dev/null
LP_NUM_THREADS=2 build/tests/peer_bench --rounds "${ROUNDS:-5}" --tris "${TRIS-10000,100000}" \
  --planes "${PLANES-5,20,60}" --psnr_pixels "${PSNR_PIXELS:-3000}" \
  --filter_yaws "${FILTER_YAWS:-}" --filter_pitch "${FILTER_PITCH:-5}" \
  --positions "${POSITIONS:-1}" --cache "${CACHE:-out/bench-filter/cache}" \
  --filter_textures "${FILTER_TEXTURES:-checker}" --data "${DATA:-../shared/data/raster}" \
  --flicker_frames "${FLICKER_FRAMES:-0}" --memory "${MEMORY:-}" \
  2> >(grep -v '\[info\]' >&2) | grep -v '\[info\]'   # progress on stderr, the tables on stdout
