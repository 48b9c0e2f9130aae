#!/usr/bin/env bash
# Frame-time benchmark: the demo scene at 1920x1080, box2 edges, trilinear textures,
# 1 and 2 threads in one run (fastest of 5 rounds of N each), then the EXR encode time of every
# compression.
# Usage: scripts/bench-frame.sh [REPEAT] [extra aperture-render flags...]
set -euo pipefail
cd "$(dirname "$0")/.."
repeat="${1:-3}"
shift || true
bin=build/engine/aperture-render
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
common=(--scene demo --size 1920x1080 --aa box2 --filter trilinear --nopreview --repeat "$repeat" "$@")

raster() { grep -oE 'raster [0-9.]+' | awk '{print $2}'; }
setup() { grep -oE 'setup [0-9.]+' | awk '{print $2}'; }
# Rounds alternate 1 and 2 threads so that a drifting machine speed biases neither.
declare -A frame=([1]=1e9 [2]=1e9)
for round in 1 2 3 4 5; do
  for t in 1 2; do
    line=$("$bin" "${common[@]}" --threads "$t" -o "$out/f.exr")
    ms=$(awk -v a="$(echo "$line" | setup)" -v b="$(echo "$line" | raster)" 'BEGIN {printf "%.1f", a + b}')
    frame[$t]=$(awk -v a="${frame[$t]}" -v b="$ms" 'BEGIN {print (b < a) ? b : a}')
  done
done
for t in 1 2; do
  echo "threads $t: frame (setup + raster, fastest of 5 rounds x $repeat) ${frame[$t]} ms"
done
awk -v a="${frame[1]}" -v b="${frame[2]}" 'BEGIN {printf "speed-up 1 -> 2 threads: %.2fx\n", a / b}'
for c in none rle zips zip piz dwaa; do
  for type in half float; do
    flag=""
    [ "$type" = float ] && flag="--float_pixels"
    line=$("$bin" "${common[@]}" --threads 2 --compression "$c" $flag -o "$out/$c.exr")
    ms=$(echo "$line" | grep -oE 'encode [0-9.]+' | awk '{print $2}')
    bytes=$(stat -c %s "$out/$c.exr")
    printf 'encode %-4s %-5s %8.1f ms %10d bytes\n' "$c" "$type" "$ms" "$bytes"
  done
done
