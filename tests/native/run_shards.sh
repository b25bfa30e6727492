#!/usr/bin/env bash
# How `make check` runs the quick native tests: one softshadow_tests process per core, each a
# gtest shard of the tests FILTER keeps, so the start of a process (and of its GL context) is paid
# once a core instead of once a test as under ctest. Non-zero, with the failing shard's log, on a
# failure.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: tests/native/run_shards.sh BUILD_DIR FILTER [SHARDS]   (FILTER: a --gtest_filter value)
set -uo pipefail
BUILD=${1:?usage: run_shards.sh BUILD_DIR FILTER [SHARDS]}
FILTER=${2:?usage: run_shards.sh BUILD_DIR FILTER [SHARDS]}
SHARDS=${3:-$(nproc)}
LOGS=$(mktemp -d)
trap 'rm -rf "$LOGS"' EXIT
pids=()
for ((i = 0; i < SHARDS; i++)); do
  SS_TEST_QUICK=1 GTEST_TOTAL_SHARDS=$SHARDS GTEST_SHARD_INDEX=$i \
    timeout 900 "$BUILD/softshadow_tests" --gtest_brief=1 --gtest_filter="$FILTER" >"$LOGS/$i.log" 2>&1 &
  pids+=($!)
done
failed=0
for ((i = 0; i < SHARDS; i++)); do
  if ! wait "${pids[$i]}"; then
    failed=1
    echo "native tests, shard $((i + 1)) of $SHARDS, failed:"
    cat "$LOGS/$i.log"
  fi
done
passed=$(awk '/^\[  PASSED  \]/ { n += $4 } END { print n + 0 }' "$LOGS"/*.log)
echo "native tests: $passed passed in $SHARDS shards$([ "$failed" -eq 0 ] || echo ", a shard failed")"
exit "$failed"
