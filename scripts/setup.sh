#!/usr/bin/env bash
# First command of the README: install what is missing, build, render the built-in demo scene.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
mkdir -p out
build/engine/aperture-render --scene demo -o out/demo.exr
echo "setup: done. Open out/demo.png (preview) or out/demo.exr."
