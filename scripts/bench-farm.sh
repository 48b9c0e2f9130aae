#!/usr/bin/env bash
# The farm benchmark, on loopback: one `aperture batch` job of FRAMES demo frames along a
# camera path (14 m up, backing away from the runway's threshold from 100 to 600 m) rendered by N
# local servers of one thread each (N in SERVERS, default "1 2 4"; this 2-core machine holds two at full speed, so
# N = 4 shows the cost of oversubscription, not of the farm). Per N it prints the job's frames/s,
# the efficiency against N x the one-server rate (and against min(N, cores) x it), and the
# distribution of the servers' own per-frame times (total_ms of every RenderFrame in their logs).
# Then the same job as a Slurm array through deploy/slurm when a Slurm cluster answers (sinfo).
#
#   scripts/bench-farm.sh                      # 200 frames, 640x360, zip
#   FRAMES=60 SIZE=320x180 SERVERS="1 2" scripts/bench-farm.sh
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${FRAMES:-200}"
size="${SIZE:-640x360}"
server_bin=build/server/aperture-server
client_bin=build/client/aperture
[ -x "$server_bin" ] && [ -x "$client_bin" ] || scripts/build.sh >/dev/null
work=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
cores=$(nproc)

cat >"$work/job.json" <<JOB
{"scene": "demo", "size": "$size", "filter": "trilinear",
 "path": {"from": "0,14,100,0,-5,0", "to": "0,14,600,0,-5,0", "frames": $frames}}
JOB

# One store for all servers, baked by the first so that no run pays the tables.
store="$work/store"
build/engine/aperture-tex bake demo --store "$store" >/dev/null

start_servers() {  # N: starts N one-thread servers; sets $servers and $logs_now
  servers=""
  logs_now=()
  for i in $(seq 1 "$1"); do
    local log="$work/server.$1.$i"
    : >"$log.out"
    "$server_bin" --listen 127.0.0.1:0 --threads 1 --store "$store" >"$log.out" 2>"$log.err" &
    pids+=("$!")
    logs_now+=("$log")
    local address=""
    for _ in $(seq 1 400); do
      address=$(sed -n 's/^listening on //p' "$log.out")
      [ -n "$address" ] && break
      sleep 0.01
    done
    [ -n "$address" ] || { echo "server did not start: $(cat "$log.err")" >&2; exit 1; }
    servers="${servers:+$servers,}$address"
  done
}
stop_servers() {
  for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; wait "$p" 2>/dev/null || true; done
  pids=()
}

echo "== farm: $frames demo frames at $size along a path, one-thread servers, $cores cores"
one_fps=""
for n in ${SERVERS:-1 2 4}; do
  start_servers "$n"
  out="$work/frames.$n"
  # Two requests in flight per server: one rendering while the other's answer travels.
  line=$("$client_bin" batch "$work/job.json" --servers "$servers" -o "$out" \
    --concurrency $((2 * n)) 2>/dev/null | grep '^batch:')
  stop_servers
  seconds=$(echo "$line" | grep -oE 'in [0-9.]+ s' | grep -oE '[0-9.]+')
  rendered=$(echo "$line" | grep -oE '[0-9]+ rendered' | grep -oE '[0-9]+')
  fps=$(awk -v f="$rendered" -v s="$seconds" 'BEGIN {printf "%.2f", f / s}')
  [ -z "$one_fps" ] && one_fps="$fps"
  # The servers' own per-frame times, from their request logs.
  cat "${logs_now[@]/%/.err}" "${logs_now[@]/%/.out}" 2>/dev/null |
    grep -oE 'rpc=RenderFrame .*total_ms=[0-9.]+' | grep -oE 'total_ms=[0-9.]+' |
    cut -d= -f2 | sort -n >"$work/times.$n"
  awk -v n="$n" -v fps="$fps" -v one="$one_fps" -v cores="$cores" -v line="$line" '
    { t[NR] = $1 }
    END {
      busy = (n < cores ? n : cores)
      printf "%d server(s): %s\n", n, line
      printf "  %.2f frames/s; efficiency %.0f %% of %d x one server, %.0f %% of %d (cores) x it\n",
             fps, 100 * fps / (n * one), n, 100 * fps / (busy * one), busy
      if (NR > 0)
        printf "  server time per frame: p10 %.1f, p50 %.1f, p90 %.1f, max %.1f ms (%d frames)\n",
               t[int(NR * 0.1) + 1], t[int(NR * 0.5) + 1], t[int(NR * 0.9) + 1], t[NR], NR
    }' "$work/times.$n"
  "$client_bin" batch "$work/job.json" --check -o "$out" | tail -1
done

if command -v sbatch >/dev/null 2>&1 && sinfo -h >/dev/null 2>&1; then
  echo "== the same job as a Slurm array: deploy/slurm/submit.sh (docs/DEPLOY.md)"
  start=$(date +%s.%N)
  deploy/slurm/submit.sh "$work/job.json" "$work/slurm-frames" 2
  echo "  slurm: $(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.1f", b - a}') s"
else
  echo "== Slurm: no cluster answers here (sinfo); ctest -L deploy runs deploy/slurm on a" \
    "private single-node cluster (tests/deploy)"
fi
