#!/bin/bash
# The installation as a user meets it.
#   check_install.sh find_package BUILD_DIR SOURCE_DIR: `cmake --install` into a temporary prefix;
#     the programs run from there and find the prefix's cost model; the runtime component alone
#     installs the four programs and no benchmark; a separate CMake project finds
#     the package, links Aperture::engine, renders the demo and writes an EXR that OpenImageIO
#     reads back.
#   check_install.sh cpack_deb BUILD_DIR SOURCE_DIR: `cpack -G DEB` makes a package with
#     dependencies; unpacked, its programs run and render a frame.
set -euo pipefail
mode=$1 build=$(realpath "$2") src=$(realpath "$3")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
version=$(sed -n 's/^project(Aperture VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")

# A program in $1/bin renders a small demo frame with no store, and names its cost model.
render_from() {
  local bin=$1/bin/aperture-render
  # (Outputs are read whole before grep: with pipefail, grep -q closing a pipe early fails it.)
  local out
  out=$("$bin" --version)
  [ "$out" = "aperture-render $version" ] || fail "$bin --version: $out"
  out=$("$1/bin/aperture-server" --help)
  grep -q -- "--cost-model" <<< "$out" || fail "aperture-server --help: $out"
  out=$("$1/bin/aperture" render --help)
  grep -q -- "--scene" <<< "$out" || fail "aperture render --help: $out"
  "$bin" --scene demo --size 64x36 --store none --nopreview -o "$tmp/frame.exr" > "$tmp/render.txt"
  grep -q "wrote $tmp/frame.exr" "$tmp/render.txt" || fail "render: $(cat "$tmp/render.txt")"
  out=$(oiiotool --info "$tmp/frame.exr")
  grep -q "64 x   36" <<< "$out" || fail "frame: $out"
}

case $mode in
find_package)
  prefix=$tmp/prefix
  cmake --install "$build" --prefix "$prefix" > "$tmp/install.log"
  for b in aperture-server aperture aperture-render aperture-tex; do
    [ -x "$prefix/bin/$b" ] || fail "bin/$b not installed"
  done
  for f in include/aperture/render/frame_renderer.h include/aperture/v1/scene.pb.h \
           lib/cmake/Aperture/ApertureConfig.cmake lib/libaperture_engine.a; do
    [ -e "$prefix/$f" ] || fail "$f not installed"
  done
  [ ! -e "$prefix/include/aperture/testing" ] || fail "test-only headers installed"
  # The runtime component is the four programs and nothing of the lab: no benchmark command.
  cmake --install "$build" --component runtime --prefix "$tmp/runtime" > "$tmp/runtime.log"
  programs=$(ls "$tmp/runtime/bin" | tr '\n' ' ')
  [ "$programs" = "aperture aperture-render aperture-server aperture-tex " ] ||
    fail "the runtime component installs: $programs"
  out=$("$tmp/runtime/bin/aperture-tex" --help)
  ! grep -q "bench" <<< "$out" || fail "the installed aperture-tex has benchmark commands: $out"
  # The cost model is found under the prefix the program runs from, not the build folder.
  mkdir -p "$prefix/share/aperture"
  echo "0.001 0.05 0.15" > "$prefix/share/aperture/cost_model.txt"
  render_from "$prefix"
  grep -q "cost model: $prefix/share/aperture/cost_model.txt" "$tmp/render.txt" ||
    fail "cost model not found under the prefix: $(cat "$tmp/render.txt")"
  out=$(APERTURE_COST_MODEL=/nonexistent "$prefix/bin/aperture-render" --scene demo --size 8x8 \
          --store none --nopreview -o "$tmp/f.exr")
  grep -q "cost model: $prefix/share" <<< "$out" ||
    fail "a missing \$APERTURE_COST_MODEL does not fall back to the prefix's: $out"
  if "$prefix/bin/aperture-render" --cost-model "$tmp/none.txt" --scene demo --size 8x8 \
       --store none --nopreview -o "$tmp/f.exr" 2> "$tmp/err.txt"; then
    fail "--cost-model of a missing file was accepted"
  fi
  grep -q "none.txt" "$tmp/err.txt" || fail "--cost-model error: $(cat "$tmp/err.txt")"

  cmake -S "$src/tests/install/consumer" -B "$tmp/consumer" -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_PREFIX_PATH="$prefix" > "$tmp/consumer-configure.log" ||
    { cat "$tmp/consumer-configure.log"; fail "find_package(Aperture) failed"; }
  cmake --build "$tmp/consumer" -j 2 > "$tmp/consumer-build.log" ||
    { tail -30 "$tmp/consumer-build.log"; fail "building against Aperture::engine failed"; }
  "$tmp/consumer/render_demo" "$tmp/consumer.exr"
  out=$(oiiotool --info "$tmp/consumer.exr")
  grep -q "96 x   54" <<< "$out" || fail "the consumer's EXR: $out"
  echo "PASS: installed to a temporary prefix; find_package(Aperture) project built and rendered"
  ;;
cpack_deb)
  (cd "$tmp" && cpack --config "$build/CPackConfig.cmake" -G DEB -B "$tmp/pkg" > "$tmp/cpack.log") ||
    { cat "$tmp/cpack.log"; fail "cpack -G DEB failed"; }
  deb=$(ls "$tmp"/pkg/*.deb)
  [ "$(dpkg-deb -f "$deb" Package)" = aperture ] || fail "package name"
  [ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || fail "package version $(dpkg-deb -f "$deb" Version)"
  depends=$(dpkg-deb -f "$deb" Depends)
  for lib in libopenimageio libtbb libgrpc; do
    echo "$depends" | grep -q "$lib" || fail "Depends lacks $lib: $depends"
  done
  dpkg-deb -x "$deb" "$tmp/root"
  render_from "$tmp/root/usr"
  echo "PASS: $(basename "$deb"), $(du -k "$deb" | cut -f1) KiB; Depends: $depends"
  ;;
*) fail "unknown mode $mode" ;;
esac
