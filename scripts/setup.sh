#!/usr/bin/env bash
# First command of the README: install what is missing, build, then the main job on the built-in
# scenes: render them locally, and through the service (a server on loopback, the client).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
mkdir -p out
# The default scene, the real airport: Schiphol's runways, taxiways and aprons from OpenStreetMap
# as a packed vector texture (seed 001), its runways' Annex 14 markings (generated packed textures)
# seen 2 NM out on the approach, hangars, cut-out trees and a glass tower cab (texture
# alpha); the same airport at night (runway, approach and taxiway lights, a town's streets, 16
# aircraft with their own lights: light points; landing and taxi lights lighting the runway and
# taxiways ahead: spot lights); then the benchmarks' synthetic airfield.
build/engine/aperture-render -o out/airport.exr
build/engine/aperture-render --scene night -o out/airport-night.exr
build/engine/aperture-render --scene demo -o out/demo.exr

# The service: a server on a free loopback port with a store of its own under out/, the client
# renders the same frame through it; the server is stopped (SIGTERM) whatever happens.
store="out/store"
: >out/server.stdout  # exists before the loop below reads it (the server opens it when it runs)
build/server/aperture-server --listen 127.0.0.1:0 --store "$store" >out/server.stdout \
  2>out/server.log &
server_pid=$!
trap 'kill "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true' EXIT
address=""
for _ in $(seq 1 200); do
  address=$(sed -n 's/^listening on //p' out/server.stdout)
  [ -n "$address" ] && break
  kill -0 "$server_pid" 2>/dev/null || { cat out/server.log >&2; exit 1; }
  sleep 0.1
done
[ -n "$address" ] || { echo "setup: the server did not start; see out/server.log" >&2; exit 1; }
build/client/aperture health --server "$address"
build/client/aperture render --server "$address" --scene airport -o out/airport-service.exr
# A simulator host for two seconds: the camera flies in while the demo's aircraft rolls down the
# runway (a scene update per frame); newest state wins, the report names late and skipped frames.
build/client/aperture sim --server "$address" --scene demo --size 1280x720 --rate 10 --frames 20
kill -TERM "$server_pid"
wait "$server_pid" || true
trap - EXIT
echo "setup: done. Open out/airport.png (by day), out/airport-night.png (at night) and" \
  "out/demo.png (previews) or their EXRs;" \
  "out/airport-service.exr came through the render service (server log: out/server.log)."
