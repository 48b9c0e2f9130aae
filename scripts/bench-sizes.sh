#!/usr/bin/env bash
# How a frame's raster time grows with its size. See --help.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() {
  cat <<'EOF'
usage: scripts/bench-sizes.sh [--help]

Raster time of the built-in scenes at sizes from 1x1 to 2560x1440 (`aperture-render --threads 2`,
the fastest of REPEAT frames a run, the median of ROUNDS runs; every round visits every scene,
size and binary in turn, so a drifting machine biases none of them). Then, per scene and binary, a
least-squares fit over the sizes of at least 320x180 pixels of

    raster(P) = a + b sqrt(P) + c P        (P: the frame's pixels)

where a is what a frame costs whatever its size, b sqrt(P) the work that grows with the length
of what the frame draws in pixels (the pixels an edge crosses, each computed exactly, and the
perimeter of each pixel's texture footprint in texels, which the exact area integral of a
packed map walks), and c P the work of each pixel. Printed: the times, the fit's terms and its
worst residual, each term's share at 1280x720 and 1920x1080, and the 1280x720 / 1920x1080 ratio
measured and predicted (the pixels' ratio is 0.444; a frame of c P alone would have it).

  --help     this text

Environment (defaults in brackets):
  SCENES   built-in scenes or scene files             [airport demo]
  SIZES    frame sizes                                [1x1 640x1 320x180 640x360 960x540
                                                       1280x720 1920x1080 2560x1440]
  ROUNDS   runs of every size                         [3]
  REPEAT   frames a run (its fastest is the run's)    [5]
  FLAGS    more aperture-render flags for every run   []
  BINS     aperture-render binaries to compare, interleaved; NAME=PATH, space-separated
           [now=build/engine/aperture-render]
EOF
}
for arg in "$@"; do
  case "$arg" in
    --help | -h) usage; exit 0 ;;
    *) echo "bench-sizes.sh: unknown argument '$arg' (see --help)" >&2; exit 2 ;;
  esac
done
scenes="${SCENES:-airport demo}"
sizes="${SIZES:-1x1 640x1 320x180 640x360 960x540 1280x720 1920x1080 2560x1440}"
rounds="${ROUNDS:-3}"
repeat="${REPEAT:-5}"
bins="${BINS:-now=build/engine/aperture-render}"
for pair in $bins; do
  bin="${pair#*=}"
  [ -x "$bin" ] || { echo "bench-sizes.sh: $bin is missing: build it first" >&2; exit 1; }
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
times="$work/times.txt"
echo "== bench-sizes: raster ms, --threads 2, fastest of $repeat a run, median of $rounds runs" >&2
for round in $(seq 1 "$rounds"); do
  for scene in $scenes; do
    for size in $sizes; do
      for pair in $bins; do
        name="${pair%%=*}"
        bin="${pair#*=}"
        # shellcheck disable=SC2086
        line=$("$bin" --scene "$scene" --size "$size" --threads 2 --repeat "$repeat" \
          --preview=false ${FLAGS:-} -o "$work/frame.exr" 2>&1) || {
          echo "bench-sizes.sh: $bin --scene $scene --size $size failed: $line" >&2
          exit 1
        }
        ms=$(echo "$line" | grep -oE 'raster [0-9.]+' | awk '{print $2}')
        echo "$name $scene $size $ms" >>"$times"
      done
    done
  done
  echo "round $round of $rounds done" >&2
done

python3 - "$times" <<'PY'
import math, statistics, sys
from collections import defaultdict

runs = defaultdict(list)
order = []
for line in open(sys.argv[1]):
    name, scene, size, ms = line.split()
    key = (name, scene)
    if key not in order:
        order.append(key)
    runs[key, size].append(float(ms))

def pixels(size):
    w, h = size.split("x")
    return int(w) * int(h)

def solve3(m, v):
    # Cramer's rule on the 3 x 3 normal equations.
    def det(a):
        return (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
                - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
                + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))
    d = det(m)
    out = []
    for k in range(3):
        mk = [row[:] for row in m]
        for i in range(3):
            mk[i][k] = v[i]
        out.append(det(mk) / d)
    return out

for name, scene in order:
    sizes = [s for (key, s) in runs if key == (name, scene)]
    sizes.sort(key=pixels)
    medians = {s: statistics.median(runs[(name, scene), s]) for s in sizes}
    print(f"{name} {scene}: " + ", ".join(f"{s} {medians[s]:.2f}" for s in sizes) + " ms")
    fit = [s for s in sizes if pixels(s) >= 320 * 180]
    if len(fit) < 4:
        print("  (fewer than 4 sizes of at least 320x180: no fit)")
        continue
    basis = lambda p: (1.0, math.sqrt(p), float(p))
    m = [[sum(basis(pixels(s))[i] * basis(pixels(s))[j] for s in fit) for j in range(3)]
         for i in range(3)]
    v = [sum(basis(pixels(s))[i] * medians[s] for s in fit) for i in range(3)]
    a, b, c = solve3(m, v)
    model = lambda p: a + b * math.sqrt(p) + c * p
    worst = max(abs(model(pixels(s)) - medians[s]) / medians[s] for s in fit)
    print(f"  fit a + b sqrt(P) + c P: a {a:.2f} ms, b {1e3 * b:.2f} us per sqrt-pixel, "
          f"c {1e6 * c:.2f} ns per pixel; worst residual {100 * worst:.1f} %")
    for s in ("1280x720", "1920x1080"):
        p = pixels(s)
        t = model(p)
        print(f"  at {s}: a {100 * a / t:.0f} %, b sqrt(P) {100 * b * math.sqrt(p) / t:.0f} %, "
              f"c P {100 * c * p / t:.0f} %")
    if "1280x720" in medians and "1920x1080" in medians:
        print(f"  1280x720 / 1920x1080: measured {medians['1280x720'] / medians['1920x1080']:.3f},"
              f" fit {model(1280 * 720) / model(1920 * 1080):.3f}, pixels 0.444")
PY
