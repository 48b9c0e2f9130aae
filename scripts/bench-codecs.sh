#!/usr/bin/env bash
# EXR codecs for frames on a network (docs/BENCHMARKS.md, "Codecs for frames on a network"): for
# the built-in airport (and the demo, the benchmarks' textured airfield) at 1280x720 and
# 1920x1080, each compression's bytes per frame, encode ms (the engine's encoder, as the server
# runs it), decode ms (OpenImageIO), the link a 30 Hz stream needs and the PSNR against the
# half-float frame (R, G, B clamped and sRGB-encoded, peak 1). Fastest of REPEAT each, on THREADS
# threads. Prints a Markdown table.
# Usage: scripts/bench-codecs.sh [REPEAT] [extra codec_bench flags...]
#   SCENES=airport,demo SIZES=1280x720,1920x1080 THREADS=2 scripts/bench-codecs.sh 5
set -euo pipefail
cd "$(dirname "$0")/.."
repeat="${1:-5}"
shift || true
bin=build/tests/codec_bench
if [ ! -x "$bin" ]; then
  cmake --build build -j "$(nproc)" --target codec_bench >/dev/null
fi
echo "$(nproc) cores; timings on a machine shared with other work vary from run to run"
# The table on stdout; the engine's log lines (tables built) on stderr.
"$bin" --scenes "${SCENES:-airport,demo}" --sizes "${SIZES:-1280x720,1920x1080}" \
  --codecs none,zip,zips,piz,dwaa,dwab,b44,b44a,rle --repeat "$repeat" \
  --threads "${THREADS:-2}" "$@"
