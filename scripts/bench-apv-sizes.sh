#!/usr/bin/env bash
# .apv sizes against the optimised PNG of the same map: for each map of ../shared/data/vector
# (2048 and 8192 texels a side), the version 1 .apv (runs uncompressed), the version 2 .apv (runs
# compressed by zstd, what `aperture-tex pack` writes) and `optipng -o2` of the map's PNG, as a
# Markdown table. Fails when a version 2 file is larger than its PNG.
#
#   scripts/bench-apv-sizes.sh [BUILD_DIR]      # default build/
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
tex=$build/engine/aperture-tex
data=../shared/data/vector
command -v optipng >/dev/null || { echo "bench-apv-sizes: optipng missing (scripts/install-deps.sh)" >&2; exit 2; }
[ -x "$tex" ] || { echo "bench-apv-sizes: $tex missing (scripts/build.sh)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
size() { stat -c %s "$1"; }
echo "| map | size | .apv v1 bytes | .apv v2 (zstd) bytes | optipng -o2 PNG bytes | v2 / PNG |"
echo "|---|---:|---:|---:|---:|---:|"
over=0
for map in osm_eham_schiphol osm_eddf_frankfurt osm_helsinki_centre; do
  for side in 2048 8192; do
    png=$data/${map}_${side}.png
    "$tex" pack "$png" -o "$work/v1.apv" --apv-version 1 >/dev/null
    "$tex" pack "$png" -o "$work/v2.apv" >/dev/null
    optipng -quiet -o2 -out "$work/opt.png" "$png"
    v1=$(size "$work/v1.apv") v2=$(size "$work/v2.apv") opt=$(size "$work/opt.png")
    ratio=$(awk -v a="$v2" -v b="$opt" 'BEGIN { printf "%.3f", a / b }')
    echo "| $map | $side | $v1 | $v2 | $opt | $ratio |"
    [ "$v2" -le "$opt" ] || over=1
    rm -f "$work/opt.png"
  done
done
if [ "$over" -ne 0 ]; then
  echo "bench-apv-sizes: a version 2 .apv is larger than its optipng -o2 PNG" >&2
  exit 1
fi
