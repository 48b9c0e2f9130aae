#!/usr/bin/env bash
# Configures (Release by default) and builds everything into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
build_type="${APERTURE_BUILD_TYPE:-Release}"
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE="$build_type"
fi
cmake --build build -j "$(nproc)"
