#!/usr/bin/env bash
# The image generator a simulator host drives: `aperture sim` against `aperture-server --threads 2`
# on this machine (127.0.0.1), swept over scenes, frame sizes and offered rates. See --help.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() {
  cat <<'EOF'
usage: scripts/bench-ig.sh [--help] [--quick]

A simulator host on RenderStream: for each scene, frame size and offered rate, `aperture sim`
(one channel, its default path: the camera flying on, the scene's named objects moving, one
SceneUpdate per frame; zip on loopback) against `aperture-server --threads 2 --listen 127.0.0.1:0`,
both on this machine. One server per scene; before each row a few frames warm it up.

One line per row:
  offered, achieved    frames requested per second, frames rendered per second (the sim's
                       achieved_hz: rendered frames from the first slot to the last frame received,
                       which over N frames reads up to about 1/N off the offered rate however fast
                       the server: rows of 100 frames and more keep that within the 1 % allowed)
  late                 rendered frames whose last byte came after the end of their own slot
                       (frame i's slot ends at start + (i + 1) / rate)
  skipped              requests the server answered as superseded by a newer state, % of offered
  delay p50/p99/max    transport delay, ms: the host's clock when it sent the state a frame shows
                       to that frame's last byte received (docs/SERVICE.md, "Transport delay")
  request ... send     its parts, medians over the frames, ms: request (host sent -> server
                       received), wait (the stream's wait + the render queue), render (update +
                       setup + raster), hold (rendered, waiting for the writer), encode (EXR),
                       send (server sent -> host received)
  CPU/frame srv, host  CPU ms per frame rendered: the server's (/proc/PID/stat utime + stime over
                       the row) and the host's (the sim's getrusage over its streaming)
  cores allow          CORES / (server + host CPU seconds per frame): the rate this machine's
                       cores could sustain with both on it
  result               PASS when achieved is within 1 % of offered, skipped <= 1 % and the delay's
                       p99 <= TARGET_P99_MS; else FAIL naming what missed

Exit status: 0 when every row passed, 3 when a row failed, 1 on an error, 2 on a bad flag.
Times on a shared machine are meaningless: run it on a quiet one.

  --quick      only 30 Hz offered, QUICK_ROW_S seconds per row (4 rows)
  --help       this text

Environment (defaults in brackets):
  SCENES         built-in scenes                            [airport demo]
  SIZES          frame sizes                                [1280x720 1920x1080]
  RATES          offered rates, Hz                          [15 20 30]
  ROW_S          seconds per row                            [10]
  QUICK_ROW_S    seconds per row with --quick               [8]
  TARGET_P99_MS  the transport delay's p99 target           [50]
  CORES          cores for "cores allow"                    [nproc]
  SIM_FLAGS      more flags for every `aperture sim` (e.g. --compression none)  []
  SERVER_BIN     [build/server/aperture-server]   CLIENT_BIN [build/client/aperture]
EOF
}

quick=0
for arg in "$@"; do
  case "$arg" in
    --help | -h) usage; exit 0 ;;
    --quick) quick=1 ;;
    *) echo "bench-ig.sh: unknown argument '$arg' (see --help)" >&2; exit 2 ;;
  esac
done
seconds="${ROW_S:-10}"
rates="${RATES:-15 20 30}"
if [ "$quick" = 1 ]; then
  seconds="${QUICK_ROW_S:-8}"
  rates="${RATES:-30}"
fi
scenes="${SCENES:-airport demo}"
sizes="${SIZES:-1280x720 1920x1080}"
target="${TARGET_P99_MS:-50}"
cores="${CORES:-$(nproc)}"
read -r -a sim_flags <<<"${SIM_FLAGS:-}"
server_bin="${SERVER_BIN:-build/server/aperture-server}"
client_bin="${CLIENT_BIN:-build/client/aperture}"
for bin in "$server_bin" "$client_bin"; do
  [ -x "$bin" ] || { echo "bench-ig.sh: $bin is missing: build it first" >&2; exit 1; }
done

work=$(mktemp -d)
pid=""
cleanup() {
  if [ -n "$pid" ]; then kill -9 "$pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT

# start_server: a server on a free loopback port; sets $address and $pid.
start_server() {
  : >"$work/server.out"
  "$server_bin" --listen 127.0.0.1:0 --threads 2 --store "$work/store" >"$work/server.out" \
    2>"$work/server.err" &
  pid=$!
  address=""
  for _ in $(seq 1 1000); do
    address=$(sed -n 's/^listening on //p' "$work/server.out")
    [ -n "$address" ] && return 0
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.01
  done
  echo "bench-ig.sh: the server did not start: $(cat "$work/server.err")" >&2
  exit 1
}
stop_server() {
  kill -TERM "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  pid=""
}
server_ticks() { awk '{print $14 + $15}' "/proc/$pid/stat"; }
tck=$(getconf CLK_TCK)

echo "== bench-ig: aperture-server --threads 2 and aperture sim on 127.0.0.1, $seconds s per row," \
  "target p99 <= $target ms, $cores cores"
printf '%-8s %-9s %7s %8s %9s %9s | %6s %6s %6s | %7s %6s %6s %6s %6s %6s | %6s %5s | %6s | %s\n' \
  scene size offered achieved late skipped "p50" "p99" "max" request wait render hold encode \
  send srv host allow result
printf '%-8s %-9s %7s %8s %9s %9s | %20s | %42s | %12s | %6s |\n' "" "" Hz Hz "" "" \
  "transport delay ms" "its parts, medians, ms" "CPU/frame ms" "Hz"
failed=0
for scene in $scenes; do
  start_server
  for size in $sizes; do
    for rate in $rates; do
      frames=$(awk -v r="$rate" -v s="$seconds" 'BEGIN {printf "%d", r * s}')
      "$client_bin" sim --server "$address" --scene "$scene" --size "$size" --rate 10 \
        --frames 3 --json "${sim_flags[@]}" >/dev/null || true
      before=$(server_ticks)
      status=0
      "$client_bin" sim --server "$address" --scene "$scene" --size "$size" --rate "$rate" \
        --frames "$frames" --json "${sim_flags[@]}" >"$work/row.json" 2>"$work/row.err" || status=$?
      after=$(server_ticks)
      if [ ! -s "$work/row.json" ]; then
        echo "bench-ig.sh: $scene $size $rate Hz: aperture sim failed ($status):" \
          "$(cat "$work/row.err")" >&2
        exit 1
      fi
      row=0
      python3 - "$work/row.json" "$scene" "$size" "$rate" "$((after - before))" "$tck" "$cores" \
        "$target" <<'PY' || row=$?
import json, sys
path, scene, size, rate, ticks, tck, cores, target = sys.argv[1:]
r = json.load(open(path))
rate, target, cores = float(rate), float(target), float(cores)
t = r["transport_delay_ms"]
ok = r["ok"]
server_ms = 1000 * int(ticks) / int(tck) / ok if ok else 0
host_ms = r["host_cpu_ms_per_frame"]
allow = 1000 * cores / (server_ms + host_ms) if server_ms + host_ms > 0 else 0
skipped = 100 * r["skipped"] / r["frames"] if r["frames"] else 0
missed = []
if abs(r["achieved_hz"] - rate) > 0.01 * rate:
    missed.append("rate")
if skipped > 1:
    missed.append("skipped")
if t["p99"] > target:
    missed.append("p99")
if r["dropped"] or r["status"] != "OK":
    missed.append("dropped %d, %s" % (r["dropped"], r["status"]))
result = "PASS" if not missed else "FAIL (" + ", ".join(missed) + ")"
late = "%d (%.0f%%)" % (r["late"], 100 * r["late"] / ok if ok else 0)
print("%-8s %-9s %7.2f %8.2f %9s %7.1f %% | %6.1f %6.1f %6.1f | %7.2f %6.2f %6.1f %6.2f %6.2f %6.2f"
      " | %6.1f %5.1f | %6.1f | %s" % (
          scene, size, rate, r["achieved_hz"], late, skipped, t["p50"], t["p99"], t["max"],
          t["request"], t["wait"], t["render"], t["hold"], t["encode"], t["send"], server_ms,
          host_ms, allow, result))
if t["unordered"]:
    print("  %d frames' clocks out of order" % t["unordered"])
sys.exit(0 if not missed else 3)
PY
      [ "$row" = 0 ] || failed=1
      [ "$row" = 0 ] || [ "$row" = 3 ] || exit 1
    done
  done
  stop_server
done
[ "$failed" = 0 ] || exit 3
