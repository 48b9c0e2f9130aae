#!/usr/bin/env bash
# deploy/slurm/ on a real Slurm: a single-node cluster (slurmctld + slurmd + munged, private
# configuration, keys and state in a temporary directory) runs deploy/slurm/submit.sh for a
# 24-frame job in 4 shards (aperture-array.sbatch, then aperture-check.sbatch):
#   1. all 24 EXRs are written, each task rendered its 6 frames, the check step passes, and every
#      frame reads back (OpenImageIO's iinfo --stats, independently of the client's own check);
#   2. frames deleted and one cut short, then the array resubmitted with one task killed
#      (scancel) while it renders: the other tasks re-render only their missing or broken frames,
#      the check step fails and names what is missing;
#   3. resubmitted again: only the frames the killed task had not written are rendered (every
#      other frame keeps its inode and mtime), and the check passes.
#
# usage: slurm_test.sh REPO_ROOT SERVER_BINARY CLIENT_BINARY
#
# Slurm and munge: Debian's slurm-wlm and munge, installed with apt-get when missing (as root, or
# through passwordless sudo). When they cannot be installed or the test is not root (slurmd must
# be), it is skipped (exit 77) -- except with CI=true, where that is a failure.
# Isolation: as root the test re-runs itself in new network, PID and mount namespaces (unshare):
# the daemons, the jobs and their aperture-servers see only a loopback interface, and when the
# test ends (pass, fail, or killed) the kernel ends every process left in the namespace. Without
# unshare the daemons run in the host's namespaces: every connection is still to 127.0.0.1, but
# slurmctld and slurmd (which have no bind-address setting) listen on all interfaces.
# Bounded: every wait has a limit; the whole run (install excluded) takes well under 5 minutes.
set -euo pipefail

repo=${1:?usage: slurm_test.sh REPO_ROOT SERVER_BINARY CLIENT_BINARY}
server=${2:?usage: slurm_test.sh REPO_ROOT SERVER_BINARY CLIENT_BINARY}
client=${3:?usage: slurm_test.sh REPO_ROOT SERVER_BINARY CLIENT_BINARY}
repo=$(cd "$repo" && pwd)

log() { echo "[slurm-test +${SECONDS}s] $*"; }
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
skip_or_fail() {
  if [ "${CI:-}" = "true" ]; then fail "$* (CI=true: the Slurm test must run)"; fi
  echo "SKIP: $*"
  exit 77
}

# --- 1. Slurm and munge -------------------------------------------------------------------------
if [ -z "${APERTURE_SLURM_TEST_NS:-}" ]; then
  # Slurm and munge, plus ip (iproute2: the private namespace's loopback) and pgrep (procps),
  # which minimal Debian images lack.
  tools=(sbatch squeue scontrol scancel sinfo slurmctld slurmd munged ip pgrep)
  missing=()
  for t in "${tools[@]}"; do
    command -v "$t" >/dev/null 2>&1 || [ -x "/usr/sbin/$t" ] || [ -x "/sbin/$t" ] || missing+=("$t")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    sudo=""
    if [ "$(id -u)" -ne 0 ]; then
      if sudo -n true 2>/dev/null; then sudo="sudo -n"; else
        skip_or_fail "Slurm is not installed (${missing[*]} missing) and this user cannot install" \
          "it (not root, no passwordless sudo): apt-get install slurm-wlm munge"
      fi
    fi
    log "installing Debian's slurm-wlm, munge, iproute2, procps (missing: ${missing[*]})"
    export DEBIAN_FRONTEND=noninteractive
    if ! { timeout 300 $sudo apt-get update -q &&
      timeout 300 $sudo apt-get install -o DPkg::Lock::Timeout=120 -y -q \
        --no-install-recommends slurm-wlm munge iproute2 procps; }; then
      skip_or_fail "apt-get could not install slurm-wlm and munge"
    fi
    log "installed: $(dpkg-query -W -f='${Package} ${Version}, ' slurm-wlm slurmd slurmctld munge)"
  fi
  [ "$(id -u)" -eq 0 ] || skip_or_fail "slurmd runs jobs as their users, so it must be root"

  # --- 2. Private namespaces: loopback only, every process gone when the test ends ------------
  if command -v ip >/dev/null 2>&1 &&
    unshare --net --pid --fork --kill-child --mount-proc true 2>/dev/null; then
    export APERTURE_SLURM_TEST_NS=private
    exec unshare --net --pid --fork --kill-child --mount-proc -- "$0" "$@"
  fi
  export APERTURE_SLURM_TEST_NS=host
fi
export PATH="$PATH:/usr/sbin:/sbin"
if [ "$APERTURE_SLURM_TEST_NS" = private ]; then
  ip link set lo up
  # Slurm binds with getaddrinfo(AI_ADDRCONFIG), which finds nothing where only loopback
  # addresses exist: give lo one more address, private to this namespace (no link leaves it).
  ip addr add 10.254.254.254/32 dev lo
  log "in private network/PID/mount namespaces (only loopback; all processes end with the test)"
else
  log "unshare unavailable: daemons in the host's namespaces, connections to 127.0.0.1 only"
fi


# --- 3. A single-node cluster on loopback -------------------------------------------------------
work=$(mktemp -d "${TMPDIR:-/tmp}/aperture-slurm-test.XXXXXX")
chmod 755 "$work"  # munged wants its socket's directory reachable by all
mkdir -p "$work/munge" "$work/state" "$work/spool" "$work/log"
chmod 700 "$work/state"
munged_pid="" slurmctld_pid="" slurmd_pid=""
deadline=$((SECONDS + 270))

dump_logs() {
  for f in "$work"/log/*.log "$work"/frames/logs/*.out; do
    [ -f "$f" ] || continue
    echo "----- $f (last 30 lines)"
    tail -n 30 "$f"
  done
}
stop_pid() {  # PID: SIGTERM, then SIGKILL after 5 s
  local pid=$1 i
  [ -n "$pid" ] || return 0
  kill -TERM "$pid" 2>/dev/null || return 0
  for ((i = 0; i < 50; i++)); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  kill -KILL "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
}
cleanup() {
  local rc=$?
  trap - EXIT
  if [ "$rc" -ne 0 ] && [ "$rc" -ne 77 ]; then dump_logs >&2 || true; fi
  if [ -n "$slurmctld_pid" ] && kill -0 "$slurmctld_pid" 2>/dev/null; then
    scancel --full --quiet $(squeue -h -o %A 2>/dev/null | sort -u) 2>/dev/null || true
    for ((i = 0; i < 100; i++)); do
      [ -z "$(squeue -h -o %A 2>/dev/null)" ] && break
      sleep 0.1
    done
  fi
  stop_pid "$slurmd_pid"
  stop_pid "$slurmctld_pid"
  stop_pid "$munged_pid"
  if [ -n "${APERTURE_SLURM_TEST_KEEP:-}" ]; then echo "kept $work"; else rm -rf "$work"; fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 143' TERM INT

# Free loopback ports for slurmctld and slurmd (in a private namespace any would do).
read -r ctld_port slurmd_port < <(/usr/bin/python3 -c 'import socket
a, b = socket.socket(), socket.socket()
a.bind(("127.0.0.1", 0)); b.bind(("127.0.0.1", 0))
print(a.getsockname()[1], b.getsockname()[1])')

# munge: a key of our own, a daemon on a socket of our own.
head -c 1024 /dev/urandom >"$work/munge/munge.key"
chmod 600 "$work/munge/munge.key"
munged --foreground --socket="$work/munge/munge.socket" --key-file="$work/munge/munge.key" \
  --log-file="$work/log/munged.log" --pid-file="$work/munge/munged.pid" \
  --seed-file="$work/munge/munged.seed" --origin=127.0.0.1 >"$work/log/munged.out" 2>&1 &
munged_pid=$!
for ((i = 0; i < 100; i++)); do [ -S "$work/munge/munge.socket" ] && break; sleep 0.1; done
if [ ! -S "$work/munge/munge.socket" ]; then
  cat "$work/log/munged.out" >&2
  fail "munged did not start"
fi

cpus=$(nproc)
node=aperture-test
cat >"$work/slurm.conf" <<EOF
# Private single-node cluster of tests/deploy/slurm_test.sh. No cgroups (no systemd as PID 1 in
# a container): processes tracked through /proc, no task binding, no accounting database.
ClusterName=aperturetest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
MailProg=/bin/true
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
MinJobAge=600
KillWait=5
Waittime=0
SlurmctldDebug=info
SlurmdDebug=info
NodeName=$node NodeHostname=$(hostname) NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=1000 State=UNKNOWN
PartitionName=render Nodes=$node Default=YES MaxTime=30 State=UP
EOF
export SLURM_CONF="$work/slurm.conf"

slurmctld -D -f "$SLURM_CONF" >"$work/log/slurmctld.out" 2>&1 &
slurmctld_pid=$!
slurmd -D -f "$SLURM_CONF" -N "$node" >"$work/log/slurmd.out" 2>&1 &
slurmd_pid=$!
state=""
for ((i = 0; i < 300; i++)); do  # up to 30 s
  state=$(sinfo -h -n "$node" -o %T 2>/dev/null || true)
  [ "$state" = idle ] && break
  kill -0 "$slurmctld_pid" 2>/dev/null || fail "slurmctld exited"
  kill -0 "$slurmd_pid" 2>/dev/null || fail "slurmd exited"
  sleep 0.1
done
[ "$state" = idle ] || fail "node $node is '$state', not idle, after 30 s"
log "$(sinfo --version), $(munged --version 2>&1 | head -n 1)"
log "cluster up: slurmctld 127.0.0.1:$ctld_port, slurmd 127.0.0.1:$slurmd_port, $cpus CPUs"
if [ "$APERTURE_SLURM_TEST_NS" = private ]; then
  # Only lo is up and has addresses here: whatever the daemons listen on is reachable only from
  # inside this namespace.
  others=$(ip -o addr show | awk '$2 != "lo"')
  [ -z "$others" ] || fail "the namespace has addresses besides lo's: $others"
fi

# --- 4. The job: 24 frames of the demo, 160x120, 4 shards of 6 ----------------------------------
frames=24 shards=4
out="$work/frames"
cp "$repo/deploy/jobs/demo-24.json" "$work/job.json"  # the shipped example: 24 frames, 160x120
export APERTURE_SERVER="$server" APERTURE_CLIENT="$client" APERTURE_STORE="$work/store"
export APERTURE_THREADS=1
name() { printf '%s/frame_%06d.exr' "$out" "$1"; }

submit() {  # -> sets array, check
  local ids
  ids=$("$repo/deploy/slurm/submit.sh" "$work/job.json" "$out" "$shards" --cpus-per-task=1 \
    --time=5)
  array=$(sed -n 's/.*array=\([0-9]*\).*/\1/p' <<<"$ids")
  check=$(sed -n 's/.*check=\([0-9]*\).*/\1/p' <<<"$ids")
  [ -n "$array" ] && [ -n "$check" ] || fail "submit.sh printed '$ids'"
  log "submitted array $array (tasks 0-$((shards - 1))) and check $check"
}
wait_jobs() {  # until the array and the check have left the queue
  while [ -n "$(squeue -h -j "$array,$check" -o %i 2>/dev/null)" ]; do
    [ "$SECONDS" -lt "$deadline" ] || fail "jobs $array, $check still queued at the deadline"
    sleep 0.2
  done
}
job_state() {  # JOBID [TASK]: JobState of a job, or of one task of an array
  local line
  while read -r line; do
    local id task st
    id=$(grep -o 'ArrayJobId=[0-9]*' <<<"$line" | cut -d= -f2)
    task=$(grep -o 'ArrayTaskId=[0-9]*' <<<"$line" | cut -d= -f2)
    st=$(grep -o 'JobState=[A-Z_]*' <<<"$line" | cut -d= -f2)
    if [ -z "${2:-}" ] || [ "$task" = "$2" ]; then
      echo "$st"
      return
    fi
    : "$id"
  done < <(scontrol -o show job "$1")
}
task_log() { echo "$out/logs/aperture-${array}_$1.out"; }
expect_task() {  # TASK STATE "SUMMARY TEXT"
  local st
  st=$(job_state "$array" "$1")
  [ "$st" = "$2" ] || fail "task $1 of array $array is $st, expected $2"
  if [ -n "${3:-}" ]; then
    grep -qF "$3" "$(task_log "$1")" || fail "task $1's log lacks '$3': $(cat "$(task_log "$1")")"
  fi
}
read_back() {  # every frame: 160 x 120, all pixels read and finite (OpenImageIO, not the client)
  local f files=() stats
  for ((f = 0; f < frames; f++)); do files+=("$(name "$f")"); done
  stats=$(iinfo --stats "${files[@]}" 2>&1) || fail "iinfo failed: $stats"
  [ "$(grep -c ' :  160 x  120, 4 channel, half openexr' <<<"$stats")" -eq "$frames" ] ||
    fail "not every frame is a 160x120 RGBA half EXR: $stats"
  [ "$(grep -c 'FiniteCount: 19200 19200 19200 19200' <<<"$stats")" -eq "$frames" ] ||
    fail "not every frame's pixels read back: $stats"
}
snapshot() {  # inode and mtime of every frame present
  local f
  for ((f = 0; f < frames; f++)); do
    [ -f "$(name "$f")" ] && echo "$f $(stat -c '%i %.9Y' "$(name "$f")")"
  done
  true
}
count_shard() {  # SHARD: frames of that shard present
  local f n=0
  for ((f = $1; f < frames; f += shards)); do [ -f "$(name "$f")" ] && n=$((n + 1)); done
  echo "$n"
}

# Run 1: the whole job.
start=$SECONDS
submit
wait_jobs
for ((t = 0; t < shards; t++)); do expect_task "$t" COMPLETED "6 rendered, 0 skipped"; done
[ "$(job_state "$check")" = COMPLETED ] || fail "check job $check is $(job_state "$check")"
grep -qF "24 valid, 0 missing, 0 invalid" "$out/logs/check-$check.out" ||
  fail "check log: $(cat "$out/logs/check-$check.out")"
[ "$(ls "$out"/frame_*.exr | wc -l)" -eq "$frames" ] || fail "not $frames frames: $(ls "$out")"
read_back
log "run 1: 24 frames in 4 shards written and valid in $((SECONDS - start)) s"

# Run 2: frames 4 (shard 0) and all of shard 2 deleted, frame 9 (shard 1) cut short; the array
# resubmitted and task 2 killed while it renders. One frame at a time, raytraced without pixel
# subdivision (about 0.15 s a frame here against 0.015 s rastered): a rastered shard of six
# 160x120 frames ends within the time it takes to see its first frame and stop its client.
for attempt in 1 2; do
  rm -f "$(name 4)"
  for ((f = 2; f < frames; f += shards)); do rm -f "$(name "$f")"; done
  truncate -s $(($(stat -c %s "$(name 9)") / 2)) "$(name 9)"
  kept_before=$(snapshot | grep -vE '^(9) ')
  start=$SECONDS
  APERTURE_CONCURRENCY=1 APERTURE_BATCH_FLAGS="--mode raytrace --max-depth 0" submit
  # Kill task 2 once it has written its first frame: its client is stopped at once (SIGSTOP, so
  # it cannot finish the shard while scancel makes its way through slurmctld and slurmd), then
  # the task is cancelled through Slurm (SIGCONT, SIGTERM, and SIGKILL after KillWait).
  while [ "$(count_shard 2)" -eq 0 ]; do
    [ "$SECONDS" -lt "$deadline" ] || fail "task 2 wrote no frame before the deadline"
    sleep 0.005
  done
  client_pid=$(pgrep -f -x -- ".* batch $work/job.json .*--shard 2/$shards .*" || true)
  [ -n "$client_pid" ] && kill -STOP $client_pid 2>/dev/null || true
  scancel "${array}_2" || true
  wait_jobs
  written=$(count_shard 2)
  if [ "$written" -lt 6 ]; then break; fi
  log "run 2: task 2 finished all 6 frames before scancel reached it; again"
  [ "$attempt" -eq 1 ] || fail "task 2 could not be killed mid-shard twice in a row"
done
expect_task 0 COMPLETED "1 rendered, 5 skipped"
expect_task 1 COMPLETED "1 rendered, 5 skipped"
expect_task 3 COMPLETED "0 rendered, 6 skipped"
st=$(job_state "$array" 2)
[ "$st" = CANCELLED ] || fail "task 2 is $st, expected CANCELLED"
[ "$(job_state "$check")" = FAILED ] ||
  fail "the check should fail with frames missing; it is $(job_state "$check")"
missing=$((6 - written))
grep -qF "$((frames - missing)) valid, $missing missing, 0 invalid" "$out/logs/check-$check.out" ||
  fail "check log: $(cat "$out/logs/check-$check.out")"
for ((f = 2; f < frames; f += shards)); do
  if [ ! -f "$(name "$f")" ]; then
    grep -qF "frame_$(printf %06d "$f").exr: missing" "$out/logs/check-$check.out" ||
      fail "the check does not name missing frame $f"
  fi
done
# Frames the rerun had no reason to touch are untouched.
unchanged=$(snapshot | grep -F -x -f <(echo "$kept_before") | wc -l)
[ "$unchanged" -eq "$(echo "$kept_before" | wc -l)" ] ||
  fail "run 2 rewrote frames that were valid"
log "run 2: task 2 killed after $written of its 6 frames; tasks 0, 1 re-rendered only frames" \
  "4 and 9; the check names the $missing missing frames and fails ($((SECONDS - start)) s)"

# Run 3: the array resubmitted once more renders exactly the frames task 2 did not write.
before=$(snapshot)
start=$SECONDS
submit
wait_jobs
expect_task 0 COMPLETED "0 rendered, 6 skipped"
expect_task 1 COMPLETED "0 rendered, 6 skipped"
expect_task 2 COMPLETED "$missing rendered, $written skipped"
expect_task 3 COMPLETED "0 rendered, 6 skipped"
[ "$(job_state "$check")" = COMPLETED ] || fail "check job $check is $(job_state "$check")"
grep -qF "24 valid, 0 missing, 0 invalid" "$out/logs/check-$check.out" ||
  fail "check log: $(cat "$out/logs/check-$check.out")"
[ "$(snapshot | grep -F -x -f <(echo "$before") | wc -l)" -eq "$((frames - missing))" ] ||
  fail "run 3 rewrote frames that were already valid"
read_back
log "run 3: the $missing missing frames rendered, the other $((frames - missing)) untouched;" \
  "all 24 valid ($((SECONDS - start)) s)"
echo "PASS ($SECONDS s)"
