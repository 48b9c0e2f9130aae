#!/usr/bin/env bash
# Issue 23's hostile soak: one aperture-server on loopback with small budgets, CLIENTS hostile
# clients (tests/bench/hostile_soak.cc) for SOAK_MIN minutes mixing valid frames (compared pixel
# for pixel with a local render), invalid requests, bombs, stalled uploads and scene churn. Prints
# the server's RSS at minute 1 and at the end, the largest store size seen (sampled every 2 s)
# against its budget, and the soak's table of status codes. Exit 1 on an unexpected status code,
# a frame that differs, RSS growth over 10 % or the store over its budget.
#
# Usage: scripts/bench-hostile.sh      (build first: scripts/build.sh)
# Environment: CLIENTS (32), SOAK_MIN (5), STORE_MB (256), SCENES_MB (1024), BUILD_DIR (build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build}"
clients="${CLIENTS:-32}"
minutes="${SOAK_MIN:-5}"
store_mb="${STORE_MB:-256}"
scenes_mb="${SCENES_MB:-1024}"
for binary in "$build/server/aperture-server" "$build/tests/hostile_soak" "$build/client/aperture"; do
  [ -x "$binary" ] || { echo "bench-hostile: $binary missing; run scripts/build.sh" >&2; exit 2; }
done

work=$(mktemp -d /tmp/aperture-hostile.XXXXXX)
server_pid=""
cleanup() {
  [ -n "$server_pid" ] && kill "$server_pid" 2>/dev/null && wait "$server_pid" 2>/dev/null
  if [ -n "${KEEP:-}" ]; then echo "kept $work"; else rm -rf "$work"; fi
}
trap cleanup EXIT

store="$work/store"
"$build/server/aperture-server" --listen 127.0.0.1:0 --threads 2 --store "$store" \
  --max-store-mb "$store_mb" --max-scenes-mb "$scenes_mb" --upload-idle-s 2 --max-queue 64 \
  >"$work/server.out" 2>"$work/server.log" &
server_pid=$!
for _ in $(seq 100); do
  grep -q '^listening on' "$work/server.out" && break
  sleep 0.1
done
address=$(sed -n 's/^listening on //p' "$work/server.out")
[ -n "$address" ] || { echo "bench-hostile: the server did not start" >&2; cat "$work/server.log"; exit 2; }
echo "== hostile soak: $clients clients, $minutes min, server $address (--max-store-mb $store_mb, --max-scenes-mb $scenes_mb, --upload-idle-s 2)"

"$build/tests/hostile_soak" --server "$address" --clients "$clients" --seconds $((minutes * 60)) \
  >"$work/soak.txt" 2>&1 &
soak_pid=$!
budget=$((store_mb * 1024 * 1024))
max_store=0
rss_minute1=""
seconds=0
rss() { awk '/^VmRSS/ {print $2}' "/proc/$server_pid/status"; }
while kill -0 "$soak_pid" 2>/dev/null; do
  sleep 2
  seconds=$((seconds + 2))
  # The server's own count of the store's entry files (complete or being written), taken while it
  # publishes nothing: a scan of the directory from outside could count a file about to be
  # trimmed together with the entry that replaced it.
  bytes=$("$build/client/aperture" info --server "$address" --deadline-s 10 2>/dev/null |
    sed -n 's/.*"storeBytes": "\([0-9]*\)".*/\1/p' || true)
  [ "${bytes:-0}" -gt "$max_store" ] && max_store=$bytes
  if [ -z "$rss_minute1" ] && [ "$seconds" -ge 60 ]; then rss_minute1=$(rss); fi
done
status=0
wait "$soak_pid" || status=$?
rss_end=$(rss)
[ -n "$rss_minute1" ] || rss_minute1=$rss_end
growth=$(awk -v a="$rss_minute1" -v b="$rss_end" 'BEGIN { printf "%.1f", (b - a) * 100 / a }')
echo "server RSS: minute 1 $((rss_minute1 / 1024)) MiB, minute $minutes $((rss_end / 1024)) MiB ($growth %)"
echo "store: largest $max_store bytes ($((max_store / 1024 / 1024)) MiB), sampled every 2 s from aperture info; budget $budget bytes ($store_mb MiB)"
cat "$work/soak.txt"
evicted=$("$build/client/aperture" info --server "$address" --deadline-s 10 2>/dev/null |
  sed -n 's/.*"storeEntriesEvicted": "\([0-9]*\)".*/\1/p' || true)
echo "store entries evicted: ${evicted:-0}; server log: $(grep -c 'upload idle' "$work/server.log" || true) idle uploads cancelled"
awk -v g="$growth" 'BEGIN { exit !(g > 10) }' && { echo "bench-hostile: RSS grew by more than 10 %"; status=1; }
[ "$max_store" -le "$budget" ] || { echo "bench-hostile: the store went over its budget"; status=1; }
exit "$status"
