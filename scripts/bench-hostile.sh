#!/usr/bin/env bash
# What hostile content and hostile clients cost the service, case by case, on loopback. Each case
# prints its times and memory; the figures and their dates live in docs/BENCHMARKS.md ("Hostile
# content and clients").
#
#   content   the scenes of tests/support/hostile_scenes.h (a crowd of 8,000 coplanar triangles 27
#             deep, 296 triangles placed 27 times each, 10 triangles in 20 layers 1 mm apart,
#             10,000 copies of a quad) and the crowds' twins spread apart in depth, by
#             aperture-render on 2 threads: raster ms (fastest of 5) at 64x48 and 1920x1080, the
#             process's peak RSS above the same scene's 1x1 frame, each crowd's 1080p raster over
#             its twin's; then through a server: the round trip and the server's peak RSS above
#             what it held before each scene (VmHWM, reset per scene)
#   update    10,000 named objects moved to one spot by one SceneUpdate, then a 1080p frame: the
#             round trip and the server's peak RSS before and after
#   budget    a frame over --max-frame-mb: the time to its RESOURCE_EXHAUSTED, then a normal frame
#   models    a glTF model whose nodes each list the next twice (2^40 triangles expanded): the
#             exit status, the time and the peak RSS of aperture-render refusing it
#   streams   2 RenderStream clients that send for 30 s and never read, then cancel: the server's
#             RSS before, at the end of the sending and after (tests/bench/hostile_streams)
#   updates   updates naming 100,000 objects, and one object 100,000 times (the same program)
#   refusals  a raytraced frame whose summed-area tables pass --max-store-mb: the time to its
#             refusal; and the server's log bytes per second under a client retrying refused
#             frames at once
#   soak      CLIENTS hostile clients (tests/bench/hostile_soak.cc) for SOAK_MIN minutes mixing
#             valid frames (compared pixel for pixel with a local render), invalid requests,
#             bombs, stalled uploads and scene churn, against a server with small budgets: its
#             RSS at minute 1 and at the end, the largest store size seen against its budget, the
#             table of status codes. Fails on an unexpected status code, a frame that differs, RSS
#             growth over 10 % or the store over its budget.
#
# Usage: scripts/bench-hostile.sh [CASE ...]   (default: every case but soak; build first:
#        scripts/build.sh)
# Environment: BUILD_DIR (build); soak: CLIENTS (32), SOAK_MIN (5), STORE_MB (256), SCENES_MB (1024)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build}"
cases=("$@")
[ ${#cases[@]} -gt 0 ] || cases=(content update budget models streams updates refusals)
for binary in server/aperture-server client/aperture engine/aperture-render tests/hostile_soak \
  tests/hostile_streams tests/make_hostile_scenes; do
  [ -x "$build/$binary" ] || { echo "bench-hostile: $build/$binary missing; run scripts/build.sh" >&2; exit 2; }
done
render="$build/engine/aperture-render"
client="$build/client/aperture"

work=$(mktemp -d /tmp/aperture-hostile.XXXXXX)
server_pid=""
stop_server() {
  if [ -n "$server_pid" ]; then
    kill "$server_pid" 2>/dev/null && wait "$server_pid" 2>/dev/null
    server_pid=""
  fi
  return 0
}
cleanup() {
  stop_server
  if [ -n "${KEEP:-}" ]; then echo "kept $work"; else rm -rf "$work"; fi
}
trap cleanup EXIT

# start_server ARGS...: a server on a free loopback port; sets server_pid and address.
start_server() {
  : >"$work/server.out"
  "$build/server/aperture-server" --listen 127.0.0.1:0 --store "$work/store" "$@" \
    >"$work/server.out" 2>"$work/server.log" &
  server_pid=$!
  address=""
  for _ in $(seq 100); do
    address=$(sed -n 's/^listening on //p' "$work/server.out")
    [ -n "$address" ] && return 0
    sleep 0.1
  done
  echo "bench-hostile: the server did not start" >&2
  cat "$work/server.log" >&2
  exit 2
}
status_kb() { awk -v key="$2:" '$1 == key {print $2}' "/proc/$1/status"; }
mib() { awk -v kb="$1" 'BEGIN { printf "%.1f", kb / 1024 }'; }
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.3f", b - a }'; }

"$build/tests/make_hostile_scenes" "$work"
frame=(--camera 0,0,0,0,0,0 --threads 2)

case_content() {
  echo "== content: aperture-render, 2 threads, raster ms (fastest of 5) and the process's peak RSS above the scene's 1x1 frame"
  printf '%-16s %12s %12s %14s %14s\n' scene "64x48 ms" "1080p ms" "64x48 +MiB" "1080p +MiB"
  declare -A raster1080
  for scene in coplanar coplanar-spread coplanar-layers stacked stacked-spread copies; do
    local file="$work/$scene.json" row=()
    /usr/bin/time -f "%M" -o "$work/peak" "$render" --scene "$file" "${frame[@]}" --size 1x1 \
      --store none --nopreview -o "$work/frame.exr" >/dev/null
    local base_kb
    base_kb=$(cat "$work/peak")
    for size in 64x48 1920x1080; do
      /usr/bin/time -f "%M" -o "$work/peak" "$render" --scene "$file" "${frame[@]}" --size "$size" \
        --repeat 5 --store none --nopreview -o "$work/frame.exr" >"$work/render.out"
      local ms
      ms=$(sed -n 's/.*raster \([0-9.]*\) ms.*/\1/p' "$work/render.out")
      row+=("$ms" "$(mib $(($(cat "$work/peak") - base_kb)))")
      [ "$size" = 1920x1080 ] && raster1080[$scene]=$ms
    done
    printf '%-16s %12s %12s %14s %14s\n' "$scene" "${row[0]}" "${row[2]}" "${row[1]}" "${row[3]}"
  done
  for crowd in coplanar stacked; do
    awk -v a="${raster1080[$crowd]}" -v b="${raster1080[$crowd-spread]}" -v c="$crowd" \
      'BEGIN { printf "%s at 1920x1080: %.2fx the same triangles spread apart in depth\n", c, a / b }'
  done
  echo "== content through the service: round trip and the server's peak RSS above what it held before the scene"
  start_server --threads 2
  for scene in coplanar coplanar-layers stacked copies; do
    echo 5 >"/proc/$server_pid/clear_refs"  # VmHWM from here
    local before_kb t
    before_kb=$(status_kb "$server_pid" VmRSS)
    t=$(now)
    "$client" render --server "$address" --scene "$work/$scene.json" --camera 0,0,0,0,0,0 \
      --size 1920x1080 -o "$work/service.exr" >/dev/null
    echo "$scene 1920x1080: $(since "$t") s, server peak +$(mib $(($(status_kb "$server_pid" VmHWM) - before_kb))) MiB"
  done
  stop_server
}

case_update() {
  echo "== update: 10,000 named objects moved to one spot by one SceneUpdate"
  start_server --threads 2
  echo "server VmRSS before: $(mib "$(status_kb "$server_pid" VmRSS)") MiB"
  "$build/tests/hostile_streams" --server "$address" --case one-spot --objects 10000 \
    --server-pid "$server_pid"
  echo "server VmHWM after: $(mib "$(status_kb "$server_pid" VmHWM)") MiB"
  stop_server
}

case_budget() {
  echo "== budget: a 1920x1080 frame of the coplanar crowd against --max-frame-mb 16"
  start_server --threads 2 --max-frame-mb 16
  local t
  t=$(now)
  "$client" render --server "$address" --scene "$work/coplanar.json" --camera 0,0,0,0,0,0 \
    --size 1920x1080 -o "$work/over.exr" >/dev/null 2>"$work/over.err" || true
  echo "refused in $(since "$t") s: $(tail -1 "$work/over.err")"
  t=$(now)
  "$client" render --server "$address" --scene "$work/coplanar.json" --camera 0,0,0,0,0,0 \
    --size 320x240 -o "$work/within.exr" >/dev/null
  echo "then a 320x240 frame within the budget in $(since "$t") s"
  stop_server
}

case_models() {
  echo "== models: aperture-render refusing a glTF model whose 40 nodes each list the next twice"
  local t rc=0
  t=$(now)
  /usr/bin/time -f "%M" -o "$work/peak" "$render" --scene "$work/dag40.gltf" --size 64x48 \
    --store none --nopreview -o "$work/dag.exr" >/dev/null 2>"$work/dag.err" || rc=$?
  echo "exit $rc in $(since "$t") s, peak RSS $(mib "$(tail -n1 "$work/peak")") MiB: $(grep -m1 error "$work/dag.err")"
}

case_streams() {
  echo "== streams: 2 RenderStream clients sending for 30 s that never read"
  start_server --threads 2
  "$build/tests/hostile_streams" --server "$address" --case unread-streams --streams 2 \
    --seconds 30 --server-pid "$server_pid"
  stop_server
}

case_updates() {
  echo "== updates: naming 100,000 objects once, and one object 100,000 times"
  start_server --threads 2
  "$build/tests/hostile_streams" --server "$address" --case big-update --objects 100000 \
    --server-pid "$server_pid"
  stop_server
}

case_refusals() {
  echo "== refusals: a raytraced frame whose summed-area tables pass --max-store-mb 64"
  cat >"$work/big-texture.json" <<'EOF'
{"name": "big texture", "textures": [{"id": "t", "checkerboard": {"size": 4096}}],
 "materials": [{"id": "m", "texture_id": "t"}],
 "meshes": [{"id": "ground", "material_id": "m", "polygons": [{"vertices": [
   {"x": -50, "y": 0, "z": 50}, {"x": 50, "y": 0, "z": 50}, {"x": 50, "y": 0, "z": -50},
   {"x": -50, "y": 0, "z": -50}]}]}]}
EOF
  start_server --threads 2 --max-store-mb 64
  local t
  t=$(now)
  "$client" render --server "$address" --scene "$work/big-texture.json" --mode raytrace \
    --camera 0,1.7,0,0,-10,0 --size 320x240 -o "$work/traced.exr" >/dev/null 2>"$work/traced.err" || true
  echo "refused in $(since "$t") s, server VmHWM $(mib "$(status_kb "$server_pid" VmHWM)") MiB: $(tail -1 "$work/traced.err")"
  stop_server
  echo "== refusals: the server's log under a client retrying refused frames for 5 s"
  start_server --threads 2 --concurrent-frames 1 --max-queue 0
  "$client" load --server "$address" --concurrency 4 --duration 5 --size 64x48 >/dev/null 2>&1 || true
  local bytes
  bytes=$(wc -c <"$work/server.log")
  echo "log: $bytes bytes in 5 s ($(awk -v b="$bytes" 'BEGIN { printf "%.1f", b / 5 / 1024 }') KiB/s), $(wc -l <"$work/server.log") lines"
  stop_server
}

case_soak() {
  local clients="${CLIENTS:-32}" minutes="${SOAK_MIN:-5}" store_mb="${STORE_MB:-256}"
  local scenes_mb="${SCENES_MB:-1024}"
  start_server --threads 2 --max-store-mb "$store_mb" --max-scenes-mb "$scenes_mb" \
    --upload-idle-s 2 --max-queue 64
  echo "== soak: $clients clients, $minutes min, server $address (--max-store-mb $store_mb, --max-scenes-mb $scenes_mb, --upload-idle-s 2)"
  "$build/tests/hostile_soak" --server "$address" --clients "$clients" \
    --seconds $((minutes * 60)) >"$work/soak.txt" 2>&1 &
  local soak_pid=$! budget=$((store_mb * 1024 * 1024)) max_store=0 rss_minute1="" seconds=0
  while kill -0 "$soak_pid" 2>/dev/null; do
    sleep 2
    seconds=$((seconds + 2))
    # The server's own count of the store's entry files (complete or being written), taken while
    # it publishes nothing: a scan of the directory from outside could count a file about to be
    # trimmed together with the entry that replaced it.
    local bytes
    bytes=$("$client" info --server "$address" --deadline-s 10 2>/dev/null |
      sed -n 's/.*"storeBytes": "\([0-9]*\)".*/\1/p' || true)
    [ "${bytes:-0}" -gt "$max_store" ] && max_store=$bytes
    if [ -z "$rss_minute1" ] && [ "$seconds" -ge 60 ]; then rss_minute1=$(status_kb "$server_pid" VmRSS); fi
  done
  local status=0
  wait "$soak_pid" || status=$?
  local rss_end
  rss_end=$(status_kb "$server_pid" VmRSS)
  [ -n "$rss_minute1" ] || rss_minute1=$rss_end
  local growth
  growth=$(awk -v a="$rss_minute1" -v b="$rss_end" 'BEGIN { printf "%.1f", (b - a) * 100 / a }')
  echo "server RSS: minute 1 $((rss_minute1 / 1024)) MiB, minute $minutes $((rss_end / 1024)) MiB ($growth %)"
  echo "store: largest $max_store bytes ($((max_store / 1024 / 1024)) MiB), sampled every 2 s from aperture info; budget $budget bytes ($store_mb MiB)"
  cat "$work/soak.txt"
  local evicted
  evicted=$("$client" info --server "$address" --deadline-s 10 2>/dev/null |
    sed -n 's/.*"storeEntriesEvicted": "\([0-9]*\)".*/\1/p' || true)
  echo "store entries evicted: ${evicted:-0}; server log: $(grep -c 'upload idle' "$work/server.log" || true) idle uploads cancelled"
  stop_server
  awk -v g="$growth" 'BEGIN { exit !(g > 10) }' && { echo "bench-hostile: RSS grew by more than 10 %"; status=1; }
  [ "$max_store" -le "$budget" ] || { echo "bench-hostile: the store went over its budget"; status=1; }
  return "$status"
}

for c in "${cases[@]}"; do
  case "$c" in
    content | update | budget | models | streams | updates | refusals | soak) "case_$c" ;;
    *) echo "bench-hostile: unknown case '$c' (content update budget models streams updates refusals soak)" >&2; exit 2 ;;
  esac
done
