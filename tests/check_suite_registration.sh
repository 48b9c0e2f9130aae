#!/usr/bin/env bash
# Every test of a GoogleTest binary is in one of the ctest entries aperture_add_test_suites made
# (a TEST whose suite the source scan missed would otherwise never run, and a filter that matches
# nothing passes).   Usage: check_suite_registration.sh BINARY FILTER...  (FILTER: A:B patterns)
set -euo pipefail
binary="$1"
shift
# Full names, Suite.Test (value-parameterised: Prefix/Suite.Test/Index), from one listing.
mapfile -t tests < <("$binary" --gtest_list_tests | awk '
  /^[^ ]/ { suite = $1; next }
  /^  /   { print suite $1 }')
covered=0
for filter in "$@"; do
  IFS=':' read -r -a patterns <<<"$filter"
  n=0
  for t in "${tests[@]}"; do
    for p in "${patterns[@]}"; do
      # shellcheck disable=SC2053  # the pattern is a glob on purpose
      if [[ $t == $p ]]; then n=$((n + 1)); break; fi
    done
  done
  if [ "$n" -eq 0 ]; then echo "FAIL: $filter matches no test" >&2; exit 1; fi
  covered=$((covered + n))
done
echo "$(basename "$binary"): $covered of ${#tests[@]} tests in $# suite entries"
[ "$covered" -eq "${#tests[@]}" ] || { echo "FAIL: $((${#tests[@]} - covered)) tests in no ctest entry" >&2; exit 1; }
