#!/usr/bin/env bash
# Service benchmarks, all on loopback, each bounded in time:
#   overhead  a 1920x1080 demo frame through the service vs the local render + encode (same run,
#             rounds interleaved);
#   restart   a server started on a baked store: time from its start to its first frame, vs a
#             server on an empty store (which builds the demo's tables first);
#   load      `aperture load` for 640x480 frames at concurrency 1, 8 and 32, LOAD_S seconds each;
#   soak      server RSS at minute 1 and at minute SOAK_MIN of a concurrency-8 load;
#   split     a 1920x1080 frame split over 2 local servers: slowest region's render
#             time over the mean, demo and skewed scenes, ROUNDS rounds, and the median;
#   node      a farm node's throughput: 1920x1080 demo frames/s from `aperture load`
#             at concurrency 1, 2 and 4, zip and none, NODE_S seconds each, against the raster-only
#             rate (1000 / the fastest local setup + raster ms on 2 threads), with the server's and
#             the client's CPU per frame and the rate the two cores allow; with BEFORE_DIR (a
#             folder holding an older aperture-server) that server is measured too, interleaved.
#   sim       a simulator host on RenderStream: `aperture sim` of the demo at 1280x720
#             and 1920x1080 at SIM_RATES (default 5 10 15 20 30), SIM_S seconds each (default 6),
#             achieved rate, late and skipped frames and latency; BEFORE_DIR as for node.
#   moving    what a moving object costs: `aperture sim` of the demo at 1920x1080,
#             5 Hz, MOVING_FRAMES frames (default 30) from one camera, with the aircraft moved by
#             a SceneUpdate every frame against no update, ROUNDS rounds interleaved; per frame
#             the server's update + setup + raster ms (median of each run), and the ratio.
#   floors    a 1920x1080 demo frame's delivery against its floors: `aperture render
#             --compression none --repeat 3` (half, the third frame of a warm connection), encode
#             ms + transport ms (round trip - the server's total) against memcpy + loopback TCP of the same bytes (scripts/bench_floors.py),
#             ROUNDS rounds interleaved, and the ratio of the medians.
#   overload  a simulator host offering 2x and 4x the sustained rate (OVERLOAD_HZ_720P, default
#             20, and OVERLOAD_HZ_1080P, default 10) for OVERLOAD_S seconds (default 10): p99
#             latency against two frame times of the sustained rate, the median latency of the
#             first and the last fifth of the frames (one camera, the aircraft taxiing: the same
#             work in every frame), skipped frames.
#   content   what real content costs: the built-in demo, the built-in airport and the
#             largest glTF model of Debian's assimp-testmodels (CONTENT_MODEL, CONTENT_CAMERA),
#             each loaded by a server on an empty store (cold: its tables are built) and by a new
#             server on that store (warm: mapped), the LoadScene ms of each, then 1920x1080 frames
#             of the three interleaved, ROUNDS rounds: the server's raster ms and the client's
#             round trip (median), and each scene's raster against the demo's.
# Usage: scripts/bench-service.sh [overhead|restart|load|soak|split|node|sim|moving|floors|
#                                  overload|content|all]   (default all)
# Environment: LOAD_S (default 60), SOAK_MIN (default 5), ROUNDS (default 5), NODE_S (default 10),
# BEFORE_DIR (unset).
set -euo pipefail
cd "$(dirname "$0")/.."
what="${1:-all}"
load_s="${LOAD_S:-60}"
soak_min="${SOAK_MIN:-5}"
rounds="${ROUNDS:-5}"
server_bin=build/server/aperture-server
client_bin=build/client/aperture
render_bin=build/engine/aperture-render
tex_bin=build/engine/aperture-tex
work=$(mktemp -d)
# Server logs are kept for a look afterwards (one line per request, errors named).
logs=out/bench-service
mkdir -p "$logs"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT

# start_server STORE [flags...]: starts a server on a free loopback port; sets $address, $pid.
start_server() {
  local store="$1"
  shift
  local log="$logs/server.$(date +%H%M%S).$RANDOM"
  log_of_last_server="$log"
  : >"$log.out"  # exists before the loop below reads it
  "$server_bin" --listen 127.0.0.1:0 --threads 2 --store "$store" "$@" >"$log.out" 2>"$log.err" &
  pid=$!
  pids+=("$pid")
  address=""
  for _ in $(seq 1 400); do
    address=$(sed -n 's/^listening on //p' "$log.out")
    [ -n "$address" ] && return 0
    sleep 0.005
  done
  echo "server did not start: $(cat "$log.err")" >&2
  exit 1
}
stop_server() { kill -TERM "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; }
ms_of() { grep -oE "$1 [0-9.]+" | head -1 | awk '{print $NF}'; }
now_ms() { date +%s%3N; }

overhead() {
  echo "== overhead: demo 1920x1080, box2, 2 threads, half/zip; fastest of $rounds rounds"
  start_server "$work/store-overhead"
  "$client_bin" render --server "$address" --scene demo --size 64x64 -o "$work/warm.exr" >/dev/null
  local best_local=1e9 best_service=1e9
  for _ in $(seq 1 "$rounds"); do
    line=$("$render_bin" --scene demo --size 1920x1080 --threads 2 --nopreview -o "$work/l.exr")
    local_ms=$(awk -v a="$(echo "$line" | ms_of setup)" -v b="$(echo "$line" | ms_of raster)" \
      -v c="$(echo "$line" | ms_of encode)" 'BEGIN {print a + b + c}')
    line=$("$client_bin" render --server "$address" --scene demo --size 1920x1080 -o "$work/s.exr")
    service_ms=$(echo "$line" | ms_of "round trip")
    best_local=$(awk -v a="$best_local" -v b="$local_ms" 'BEGIN {print (b < a) ? b : a}')
    best_service=$(awk -v a="$best_service" -v b="$service_ms" 'BEGIN {print (b < a) ? b : a}')
  done
  stop_server
  awk -v l="$best_local" -v s="$best_service" 'BEGIN {
    printf "local setup+raster+encode %.1f ms, service round trip %.1f ms: %.3fx\n", l, s, s / l }'
}

restart() {
  echo "== restart: a server (re)started on a baked store vs an empty one; demo frame, aniso"
  "$tex_bin" bake demo --store "$work/store-baked" | tail -1
  for size in 640x480 1920x1080; do
    for store in baked empty; do
      for _ in $(seq 1 3); do
        local t0 t1 t2
        t0=$(now_ms)
        start_server "$work/store-$store"
        t1=$(now_ms)
        "$client_bin" render --server "$address" --scene demo --size "$size" --filter aniso \
          -o "$work/r.exr" >/dev/null
        t2=$(now_ms)
        stop_server
        # Server-side work of the first frame: loading the scene (textures, tables) and the frame.
        local log="${log_of_last_server}.err"
        local work_ms
        work_ms=$(awk '/rpc=LoadScene/ {for (i = 1; i <= NF; i++) if ($i ~ /^ms=/) s += substr($i, 4)}
                       /rpc=RenderFrame/ {for (i = 1; i <= NF; i++) if ($i ~ /^total_ms=/) s += substr($i, 10)}
                       END {printf "%.0f", s}' "$log")
        echo "$size store $store: listening after $((t1 - t0)) ms; scene load + first frame" \
          "$work_ms ms in the server: $((t1 - t0 + work_ms)) ms; client end to end $((t2 - t0)) ms"
        [ "$store" = empty ] && rm -rf "$work/store-empty"
      done
    done
  done
}

load() {
  echo "== load: 640x480 demo frames, $load_s s per concurrency, server --threads 2"
  start_server "$work/store-load" --max-queue 64
  for c in 1 8 32; do
    "$client_bin" load --server "$address" --scene demo --size 640x480 --concurrency "$c" \
      --duration "$load_s" | sed "s/^/concurrency $c: /"
  done
  stop_server
}

rss_kb() { awk '/VmRSS/ {print $2}' "/proc/$1/status"; }

soak() {
  echo "== soak: concurrency 8, 640x480, $soak_min min; server RSS at minute 1 and at the end"
  start_server "$work/store-soak" --max-queue 64
  "$client_bin" load --server "$address" --scene demo --size 640x480 --concurrency 8 \
    --duration $((soak_min * 60)) >"$work/soak.txt" &
  local load_pid=$!
  pids+=("$load_pid")
  sleep 60
  local first
  first=$(rss_kb "$pid")
  echo "minute 1: RSS $((first / 1024)) MiB"
  wait "$load_pid"
  local last
  last=$(rss_kb "$pid")
  echo "minute $soak_min: RSS $((last / 1024)) MiB"
  sed 's/^/soak load: /' "$work/soak.txt"
  awk -v a="$first" -v b="$last" 'BEGIN {printf "RSS growth minute 1 -> end: %+.1f%%\n", 100 * (b - a) / a}'
  stop_server
  echo "requests the server did not answer OK (log ${log_of_last_server}.err):"
  grep -c "rpc=RenderFrame.*status=" "${log_of_last_server}.err" | sed 's/^/  RenderFrame lines: /'
  grep "rpc=RenderFrame" "${log_of_last_server}.err" | grep -v "status=OK" | head -5 || true
}

split() {
  echo "== split: 1920x1080 over 2 local servers (--threads 1 each), $rounds rounds per scene"
  # The plan is only as good as the cost model: fit it on this machine once (about a minute).
  export APERTURE_COST_MODEL=${APERTURE_COST_MODEL:-build/share/aperture/cost_model.txt}
  [ -f "$APERTURE_COST_MODEL" ] || "$render_bin" --calibrate --cost-model "$APERTURE_COST_MODEL" | tail -1
  start_server "$work/store-split" --threads 1
  local a="$address" pid_a="$pid"
  start_server "$work/store-split" --threads 1
  local b="$address"
  for scene in demo skewed; do
    # One full-size round first: a server's first frames of a size also pay for growing its heap.
    "$client_bin" render --split 2 --servers "$a,$b" --scene "$scene" --size 1920x1080 \
      -o "$work/w.exr" >/dev/null
    for _ in $(seq 1 "$rounds"); do
      "$client_bin" render --split 2 --servers "$a,$b" --scene "$scene" --size 1920x1080 \
        -o "$work/split.exr" | grep -oE 'slowest / mean [0-9.]+' | awk '{print $4}'
    done | sort -n | awk -v s="$scene" '{r[NR] = $1} END {
      printf "%s: slowest / mean region render time, %d rounds: min %.3f median %.3f max %.3f\n",
             s, NR, r[1], r[int((NR + 1) / 2)], r[NR] }'
  done
  stop_server
  pid="$pid_a"
  stop_server
}

node() {
  local node_s="${NODE_S:-10}"
  local line raster_fps
  line=$("$render_bin" --scene demo --size 1920x1080 --threads 2 --repeat 5 --nopreview \
    -o "$work/local.exr")
  raster_fps=$(awk -v a="$(echo "$line" | ms_of setup)" -v b="$(echo "$line" | ms_of raster)" \
    'BEGIN {printf "%.2f", 1000 / (a + b)}')
  echo "== node: demo 1920x1080 half, server --threads 2, $node_s s per cell;" \
    "raster-only $raster_fps frames/s"
  local builds=("$server_bin")
  [ -n "${BEFORE_DIR:-}" ] && builds=("$BEFORE_DIR/aperture-server" "$server_bin")
  # CPU per frame of the server (/proc/PID/stat utime + stime) and of the client (the shell's
  # `times` for its children), and the frame rate the two cores allow with both on this machine:
  # 2 cores / (server + client CPU per frame); and with the client elsewhere: 2 / server.
  local tck
  tck=$(getconf CLK_TCK)
  server_cpu() { awk '{print $14 + $15}' "/proc/$pid/stat"; }
  for c in zip none; do
    for n in 1 2 4; do
      for bin in "${builds[@]}"; do
        server_bin="$bin" start_server "$work/store-node" --max-queue 64
        "$client_bin" render --server "$address" --scene demo --size 1920x1080 \
          -o "$work/warm.exr" >/dev/null
        local before after report client
        before=$(server_cpu)
        report=$( { "$client_bin" load --server "$address" --scene demo --size 1920x1080 \
          --compression "$c" --concurrency "$n" --duration "$node_s" --json; times; } )
        after=$(server_cpu)
        # `times` prints the shell's then its children's user and system time (XmY.YYYs).
        client=$(echo "$report" | tail -1 | awk '{
          t = 0; for (i = 1; i <= 2; ++i) { split($i, p, "m"); sub(/s/, "", p[2]);
          t += p[1] * 60 + p[2] } printf "%.3f", t }')
        echo "$report" | grep '"frames_per_s"' |
          awk -v b="$bin" -v c="$c" -v n="$n" -v r="$raster_fps" -v s="$node_s" \
            -v sv="$(( after - before ))" -v tck="$tck" -v cl="$client" '{
            match($0, /"frames_per_s": *[0-9.]+/); f = substr($0, RSTART, RLENGTH);
            sub(/.*: */, "", f);
            frames = f * s; scpu = 1000 * sv / tck / frames; ccpu = 1000 * cl / frames;
            printf "%-28s %-4s concurrency %d: %6.2f frames/s, %3.0f %% of raster-only;" \
                   " CPU per frame: server %.1f ms, client %.1f ms; the cores allow %.2f" \
                   " frames/s (%.0f %% reached), %.2f with the client elsewhere\n",
                   b, c, n, f, 100 * f / r, scpu, ccpu, 2000 / (scpu + ccpu),
                   100 * f * (scpu + ccpu) / 2000, 2000 / scpu }'
        stop_server
      done
    done
  done
}

sim() {
  local sim_s="${SIM_S:-6}"
  echo "== sim: demo on RenderStream, server --threads 2, $sim_s s per rate"
  local builds=("$server_bin")
  [ -n "${BEFORE_DIR:-}" ] && builds=("$BEFORE_DIR/aperture-server" "$server_bin")
  for size in 1280x720 1920x1080; do
    for rate in ${SIM_RATES:-5 10 15 20 30}; do
      for bin in "${builds[@]}"; do
        server_bin="$bin" start_server "$work/store-sim" --max-queue 64
        "$client_bin" render --server "$address" --scene demo --size "$size" \
          -o "$work/warm.exr" >/dev/null
        local frames
        frames=$(awk -v r="$rate" -v s="$sim_s" 'BEGIN {printf "%d", r * s}')
        "$client_bin" sim --server "$address" --scene demo --size "$size" --rate "$rate" \
          --frames "$frames" --json | sed "s|^|$bin $size $rate Hz: |" || true
        stop_server
      done
    done
  done
}

# The median over a server log's RenderStream frames of update + setup + raster ms.
frame_work_ms() {
  grep 'rpc=RenderStream scene=' "$1" |
    sed -E 's/.*update_ms=([0-9.]+).*setup_ms=([0-9.]+) raster_ms=([0-9.]+).*/\1 \2 \3/' |
    awk '{print $1 + $2 + $3}' | sort -n |
    awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'
}

moving() {
  local frames="${MOVING_FRAMES:-30}"
  echo "== moving: demo 1920x1080 at 5 Hz, $frames frames from one camera, $rounds rounds"
  local camera='"camera": {"position": {"x": 0, "y": 14, "z": 420}, "pitchDeg": -5}'
  : >"$work/static.jsonl"
  : >"$work/moving.jsonl"
  for i in $(seq 0 $((frames - 1))); do
    echo "{$camera}" >>"$work/static.jsonl"
    awk -v i="$i" -v c="$camera" 'BEGIN {printf "{%s, \"update\": {\"objects\": [{\"name\": \"aircraft\", \"transform\": {\"translation\": {\"x\": %.2f, \"z\": %.2f}, \"yawDeg\": %.2f}}]}}\n", c, -0.1 * i, 50 - 1.5 * i, 0.5 * i}' >>"$work/moving.jsonl"
  done
  local ratios=()
  for round in $(seq 1 "$rounds"); do
    local static_ms moving_ms
    for kind in static moving; do
      start_server "$work/store-moving"
      "$client_bin" sim --server "$address" --scene demo --size 1920x1080 --rate 5 \
        --path "$work/$kind.jsonl" --frames "$frames" --json >"$work/$kind.json" || true
      stop_server
      local ms
      ms=$(frame_work_ms "$log_of_last_server.err")
      [ "$kind" = static ] && static_ms=$ms || moving_ms=$ms
      echo "round $round $kind: median update+setup+raster $ms ms; $(cat "$work/$kind.json")"
    done
    ratios+=("$(awk -v m="$moving_ms" -v s="$static_ms" 'BEGIN {printf "%.3f", m / s}')")
    echo "round $round: moving / static = ${ratios[-1]}"
  done
  printf '%s\n' "${ratios[@]}" | sort -n |
    awk '{v[NR] = $1} END {printf "moving / static, median of %d rounds: %s\n", NR, v[int((NR + 1) / 2)]}'
}

median() { sort -n | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

floors() {
  echo "== floors: demo 1920x1080 half, compression none, $rounds rounds"
  start_server "$work/store-floors"
  "$client_bin" render --server "$address" --scene demo --size 64x64 -o "$work/warm.exr" >/dev/null
  : >"$work/delivery"
  : >"$work/floor"
  for round in $(seq 1 "$rounds"); do
    local line bytes encode total trip
    # The third frame on one connection: a live channel's connection is warm (gRPC's flow-control
    # windows have grown; the first frame of a fresh connection pays their ramp).
    line=$("$client_bin" render --server "$address" --scene demo --size 1920x1080 \
      --compression none --repeat 3 -o "$work/f.exr" | grep -E '^frame|^wrote' | tail -2)
    encode=$(echo "$line" | ms_of encode)
    total=$(echo "$line" | ms_of server)
    trip=$(echo "$line" | ms_of "round trip")
    bytes=$(echo "$line" | sed -nE 's/.*\(([0-9]+) bytes\).*/\1/p')
    local delivery
    delivery=$(awk -v e="$encode" -v t="$total" -v r="$trip" 'BEGIN {print e + r - t}')
    local floor
    floor=$(python3 scripts/bench_floors.py "$bytes" --rounds 3 |
      awk '{print $2 + $4}')
    echo "$delivery" >>"$work/delivery"
    echo "$floor" >>"$work/floor"
    echo "round $round: $bytes bytes; encode $encode ms + transport $(awk -v t="$total" -v r="$trip" 'BEGIN {print r - t}') ms = $delivery ms; floor (memcpy + loopback) $floor ms"
  done
  stop_server
  awk -v d="$(median <"$work/delivery")" -v f="$(median <"$work/floor")" 'BEGIN {
    printf "median encode + transport %.2f ms, floor %.2f ms: %.2fx the floor\n", d, f, d / f }'
}

overload() {
  local seconds="${OVERLOAD_S:-10}"
  echo "== overload: demo on RenderStream, server --threads 2, $seconds s per rate"
  for spec in "1280x720 ${OVERLOAD_HZ_720P:-20}" "1920x1080 ${OVERLOAD_HZ_1080P:-10}"; do
    set -- $spec
    local size="$1" sustained="$2"
    for factor in 2 4; do
      local rate=$((sustained * factor))
      # One camera, the aircraft taxiing slowly: the same work in every frame, so the first and
      # the last fifth differ only if a backlog builds.
      : >"$work/overload.jsonl"
      for i in $(seq 0 $((rate * seconds - 1))); do
        awk -v i="$i" 'BEGIN {printf "{\"camera\": {\"position\": {\"x\": 0, \"y\": 14, \"z\": 420}, \"pitchDeg\": -5}, \"update\": {\"objects\": [{\"name\": \"aircraft\", \"transform\": {\"translation\": {\"y\": 0.15, \"z\": %.3f}}}]}}\n", 50 - 0.01 * i}' >>"$work/overload.jsonl"
      done
      start_server "$work/store-overload" --max-queue 64
      "$client_bin" render --server "$address" --scene demo --size "$size" -o "$work/warm.exr" \
        >/dev/null
      "$client_bin" sim --server "$address" --scene demo --size "$size" --rate "$rate" \
        --frames $((rate * seconds)) --path "$work/overload.jsonl" --json >"$work/overload.json" ||
        true
      stop_server
      local budget
      budget=$(awk -v r="$sustained" 'BEGIN {printf "%.0f", 2000 / r}')
      echo "$size offered $rate Hz (${factor}x $sustained Hz; p99 bar $budget ms): $(cat "$work/overload.json")"
    done
  done
}

content() {
  local model="${CONTENT_MODEL:-/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb}"
  local model_camera="${CONTENT_CAMERA:-0,150,900,0,-10,0}"
  echo "== content: demo, airport and $(basename "$model") at 1920x1080, server --threads 2"
  local names=(demo airport model) scenes=(demo airport "$model") cameras=("" "" "$model_camera")
  # LoadScene ms of one scene from the server's log (its only load).
  load_ms() { awk '/rpc=LoadScene/ {for (i = 1; i <= NF; i++) if ($i ~ /^ms=/) print substr($i, 4)}' "$1" | head -1; }
  for i in 0 1 2; do
    local camera_flag=()
    [ -n "${cameras[$i]}" ] && camera_flag=(--camera "${cameras[$i]}")
    for store in cold warm; do
      start_server "$work/store-content-$i"
      "$client_bin" render --server "$address" --scene "${scenes[$i]}" "${camera_flag[@]}" \
        --size 64x36 -o "$work/c.exr" >/dev/null 2>>"$work/content.err"
      stop_server
      echo "${names[$i]}: LoadScene $store store $(load_ms "${log_of_last_server}.err") ms"
    done
  done
  start_server "$work/store-content-all" --max-queue 8
  for i in 0 1 2; do  # loads (and warms) each scene once
    local camera_flag=()
    [ -n "${cameras[$i]}" ] && camera_flag=(--camera "${cameras[$i]}")
    "$client_bin" render --server "$address" --scene "${scenes[$i]}" "${camera_flag[@]}" \
      --size 64x36 -o "$work/c.exr" >/dev/null 2>>"$work/content.err"
  done
  : >"$work/content.txt"
  for _ in $(seq 1 "$rounds"); do
    for i in 0 1 2; do
      local camera_flag=()
      [ -n "${cameras[$i]}" ] && camera_flag=(--camera "${cameras[$i]}")
      line=$("$client_bin" render --server "$address" --scene "${scenes[$i]}" "${camera_flag[@]}" \
        --size 1920x1080 -o "$work/c.exr" 2>>"$work/content.err")
      echo "${names[$i]} $(echo "$line" | ms_of raster) $(echo "$line" | ms_of "round trip")" \
        >>"$work/content.txt"
    done
  done
  stop_server
  awk '
    function median(list, n,   sorted, i, j, t) {
      for (i = 1; i <= n; i++) sorted[i] = list[i]
      for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++)
        if (sorted[j] < sorted[i]) { t = sorted[i]; sorted[i] = sorted[j]; sorted[j] = t }
      return (n % 2) ? sorted[(n + 1) / 2] : (sorted[n / 2] + sorted[n / 2 + 1]) / 2
    }
    { n[$1]++; raster[$1, n[$1]] = $2; trip[$1, n[$1]] = $3 }
    END {
      split("demo airport model", order, " ")
      for (k = 1; k <= 3; k++) {
        s = order[k]
        for (i = 1; i <= n[s]; i++) { r[i] = raster[s, i]; t[i] = trip[s, i] }
        mr[s] = median(r, n[s]); mt[s] = median(t, n[s])
        printf "%s 1920x1080: raster %.1f ms, round trip %.1f ms (median of %d); raster %.2fx the demo\n",
          s, mr[s], mt[s], n[s], mr[s] / mr["demo"]
      }
    }' "$work/content.txt"
}

case "$what" in
  overhead | restart | load | soak | split | node | sim | moving | floors | overload | content)
    "$what" ;;
  all) overhead; restart; load; soak; split; node; sim; moving; floors; overload; content ;;
  *) echo "usage: $0 [overhead|restart|load|soak|split|node|sim|moving|floors|overload|content|all]" >&2
     exit 2 ;;
esac
