#!/usr/bin/env bash
# Runs a libFuzzer target for ctest: run-fuzzer.sh LOG ARTIFACTS FUZZER [ARGS...].
# The fuzzer's output (every NEW and REDUCE line, and the decoders' messages) goes to LOG; on
# success the final statistics are printed, on failure the log's last 80 lines (the sanitizer's
# or libFuzzer's report) and each input the fuzzer saved under ARTIFACTS, in base64, so that a
# failure in CI can be reproduced from its printed output alone:
#   base64 -d > crash && FUZZER crash
set -uo pipefail
if [ $# -lt 3 ]; then
  echo "usage: run-fuzzer.sh LOG ARTIFACTS FUZZER [ARGS...]" >&2
  exit 2
fi
log=$1 artifacts=$2
shift 2
mkdir -p "$artifacts"
"$@" -artifact_prefix="$artifacts/" > "$log" 2>&1
status=$?
if [ $status -eq 0 ]; then
  grep -E '^(stat::|Done )' "$log"
  exit 0
fi
echo "fuzzer exited with status $status; the last 80 lines of $log (without libpng's messages):"
grep -v "^libpng error" "$log" | tail -n 80
for input in "$artifacts"/*; do
  [ -f "$input" ] || continue
  echo "saved input $(basename "$input") ($(stat -c %s "$input") bytes), base64:"
  head -c 16384 "$input" | base64 -w 100
done
exit $status
