#!/usr/bin/env bash
# Do light points blink? Aperture against Mesa llvmpipe (OSMesa, LP_NUM_THREADS=2) drawing the
# same lights as osgSim-based image generators do, on a slow approach to a lit runway, then a light
# passing behind a wall's edge (tests/bench/light_blink_bench.cc says what each table measures).
# About 20 s with the defaults on 2 cores (about 30 s with all three filters).
# `load`: what the night scene's lights cost, Aperture against llvmpipe drawing the same frame
# (tests/bench/night_load_bench.cc).
set -euo pipefail
cd "$(dirname "$0")/.."

usage() {
  cat <<'EOF'
usage: scripts/bench-lights.sh [--help] [light_blink_bench flags...]
       scripts/bench-lights.sh load [--help] [night_load_bench flags...]

Builds build/tests/light_blink_bench or night_load_bench (installing Debian's libosmesa6-dev first
when it is missing: a benchmark dependency, not a product one) and runs it once with
LP_NUM_THREADS=2 (`load`: with glibc keeping freed memory mapped, GLIBC_TUNABLES, so that frames
do not pay for each other's page faults).

Without a mode, do light points blink?

  blink  a 3 degree approach at 70 m/s, 60 frames/s, towards the runway scene (266 edge, centre
         line, threshold, end and approach lights): per light, the ripple (max - min) / mean of
         its energy over its analytic energy, for Aperture (box2) and for llvmpipe's smooth GL
         points 1x and 4x MSAA (osgSim's minimum point sizes 1.5 and 0); the median, the worst
         light and the worst of each row of lights. Aperture's target: ripple at most 1 %.
  edge   a light 1 km away passing behind the slanted edge of a wall 100 m away: its energy per
         frame beside the analytic visible share of its footprint; Aperture monotone, each step
         the covered area's change; llvmpipe's points depth tested, popping.

Tables on stdout, progress on stderr. The exit status is the benchmark's: 0 when Aperture met its
targets, 3 when it did not, 1 on an error, 2 on a bad flag.

Environment (defaults in brackets):
  SIZES        frame sizes, WxH[,WxH]                               [1280x720]
  FRAMES       frames of the approach                               [180, 3 s at 60 frames/s]
  AA           Aperture's filters, of box2, box1, tent2             [box2]
  SCENE        runway, an engine built-in scene, or a scene file    [runway]
  EDGE_FRAMES  frames of the light behind an edge (0: none)         [120]
  CSV          a file for every light's every frame                 [none]
  PREVIEW      a path prefix for Aperture's first frame as PNG      [none]

Any further flags go to the benchmark after these (build/tests/light_blink_bench --help lists
them: --aim, --heading, --start_m to fly towards another scene's runway, --peer_min_sizes, ...).

load: the night scene's load (--scene night, about 25,500 lights in view, 18,100 of them visible) on 2 threads

  The night frame from its camera with its light points, without them, and the same polygons by
  day (night-by-day), each size in interleaved rounds after a warm-up: Aperture (--threads 2,
  box2; its frame is projection + raster, the light pass part of the raster) and llvmpipe drawing
  the same frame as a GL image generator does (the scene's polygons as textured triangles,
  trilinear mip-maps, 4x MSAA and 1x, the lights as osgSim's points sized every frame). A table
  per size of medians: with lights, without, by day, the lights' cost (with - without) / without
  and night / day. Aperture's targets: the lights' cost at most 15 %, night at most 1.5x day
  (exit status 0 when met at every size, 3 when not). The warm-up round's frames go to OUT
  (Aperture's as EXR and PNG, llvmpipe's as PNG) to look at. Several minutes with the defaults
  on 2 cores: run it on a quiet machine.

  SIZES        frame sizes, WxH[,WxH]                               [1280x720,1920x1080]
  ROUNDS       timed rounds after the warm-up                       [5]
  MSAA         llvmpipe's sample counts, of 4 and 1                 [4,1]
  OUT          the warm-up round's frames (empty: none)             [out/night-load]

Any further flags go to night_load_bench after these (build/tests/night_load_bench --help lists
them: --aa, --peer_min_size, --peer_texture_side, --peer_near, --encode).

  scripts/bench-lights.sh                                   # the defaults
  AA=box2,box1,tent2 scripts/bench-lights.sh                # every filter
  SIZES=640x360 FRAMES=60 EDGE_FRAMES=40 scripts/bench-lights.sh   # a quick look
  SCENE=airfield.json scripts/bench-lights.sh --aim X,Y,Z --heading DEG   # another runway
  SCENE=night EDGE_FRAMES=0 scripts/bench-lights.sh --aim 0,0,-100 --start_m 2150 \
    --groups approach,runway-threshold,runway-edge,runway-centre,touchdown-zone,runway-end
                                       # the night scene's runway and approach lights (36L, 36C)
  scripts/bench-lights.sh load                              # the night scene's load
  SIZES=1280x720 ROUNDS=1 scripts/bench-lights.sh load      # a quick look at the load
EOF
}

mode=blink
if [ "${1:-}" = "load" ]; then
  mode=load
  shift
fi

for arg in "$@"; do
  if [ "$arg" = "--help" ] || [ "$arg" = "-h" ]; then
    usage
    exit 0
  fi
done

if ! dpkg-query -W -f='${Status}' libosmesa6-dev 2>/dev/null | grep -q "install ok installed"; then
  echo "bench-lights: installing libosmesa6-dev (benchmark dependency)" >&2
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
if [ "$mode" = "load" ]; then
  cmake --build build -j "$(nproc)" --target night_load_bench >/dev/null
  # Both renderers' frame buffers stay mapped from frame to frame (glibc's mmap off, no trim), as
  # in a long-running process: otherwise each 1920x1080 frame may pay again for pages the last
  # one gave back, which on some virtual machines swings a variant by tens of milliseconds.
  GLIBC_TUNABLES="${GLIBC_TUNABLES:-glibc.malloc.mmap_max=0:glibc.malloc.trim_threshold=17179869184}" \
  LP_NUM_THREADS=2 exec build/tests/night_load_bench --threads 2 \
    --sizes "${SIZES:-1280x720,1920x1080}" --rounds "${ROUNDS:-5}" --msaa "${MSAA:-4,1}" \
    --out "${OUT-out/night-load}" "$@"
fi
cmake --build build -j "$(nproc)" --target light_blink_bench >/dev/null
args=(--scene "${SCENE:-runway}" --sizes "${SIZES:-1280x720}" --frames "${FRAMES:-180}"
      --aa "${AA:-box2}" --edge_frames "${EDGE_FRAMES:-120}")
if [ -n "${CSV:-}" ]; then args+=(--csv "$CSV"); fi
if [ -n "${PREVIEW:-}" ]; then args+=(--preview "$PREVIEW"); fi
LP_NUM_THREADS=2 exec build/tests/light_blink_bench "${args[@]}" "$@"
