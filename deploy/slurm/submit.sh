#!/usr/bin/env bash
# Submits an `aperture batch` job to Slurm as an array of N shards plus a final check.
#
#   deploy/slurm/submit.sh JOB.json OUT_DIR N [sbatch options for the array...]
#
# OUT_DIR must be on a file system every node sees. Logs go to OUT_DIR/logs/. Prints the array's
# and the check's job ids ("array=ID check=ID"). Run it again after a failure (a killed task, a
# lost node): every task skips the frames already valid and renders only the missing ones.
# Options after N go to the array's sbatch (e.g. --partition=render --cpus-per-task=16
# --time=2:00:00 --array=1,3 to rerun only those shards).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
job=${1:?usage: submit.sh JOB.json OUT_DIR N [sbatch options...]}
out=${2:?usage: submit.sh JOB.json OUT_DIR N [sbatch options...]}
shards=${3:?usage: submit.sh JOB.json OUT_DIR N [sbatch options...]}
shift 3
[[ $shards =~ ^[1-9][0-9]*$ ]] || { echo "submit.sh: N must be a positive integer" >&2; exit 2; }
[ -f "$job" ] || { echo "submit.sh: no job file $job" >&2; exit 2; }
job=$(cd "$(dirname "$job")" && pwd)/$(basename "$job")
mkdir -p "$out/logs"
out=$(cd "$out" && pwd)

array=$(sbatch --parsable --array="0-$((shards - 1))" --output="$out/logs/aperture-%A_%a.out" \
  "$@" "$here/aperture-array.sbatch" "$job" "$out" "$shards")
array=${array%%;*}
check=$(sbatch --parsable --dependency="afterany:$array" --output="$out/logs/check-%j.out" \
  "$here/aperture-check.sbatch" "$job" "$out")
check=${check%%;*}
echo "array=$array check=$check"
