#!/usr/bin/env bash
# How the add-on is tested: every tests/blender/test_*.py in a fresh headless Blender.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: tests/blender/run.sh BUILD_DIR   (prints "N passed, N failed"; non-zero on a failure)
set -uo pipefail
BUILD_DIR=${1:?usage: run.sh BUILD_DIR}
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
BUILD_DIR=$(cd "$BUILD_DIR" && pwd)
export SOFTSHADOW_LIB="$BUILD_DIR/libsoftshadow.so"
export SOFTSHADOW_ADDON_PATH="$ROOT/blender_addon"
export SOFTSHADOW_BUILD_DIR="$BUILD_DIR"
export SOFTSHADOW_ROOT="$ROOT"
BLENDER=${BLENDER:-blender}
LOGS=$(mktemp -d)
passed=0; failed=0; failures=()
for test in "$HERE"/test_*.py; do
  name=$(basename "$test" .py)
  log="$LOGS/$name.log"
  if timeout 900 "$BLENDER" --background --factory-startup --python-exit-code 1 \
       --python "$test" >"$log" 2>&1 && grep -q "^SOFTSHADOW-TEST-OK" "$log"; then
    passed=$((passed + 1)); echo "PASS $name"
  else
    failed=$((failed + 1)); failures+=("$name"); echo "FAIL $name"
    tail -n 40 "$log" | sed 's/^/    /'
  fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
