#!/usr/bin/env bash
# How the add-on is tested: each tests/blender/test_*.py in a fresh headless Blender, against the
# source tree or against the add-on installed from the zip.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: tests/blender/run.sh BUILD_DIR [TEST...]                 the source tree + BUILD_DIR's library
#        tests/blender/run.sh --zip ZIP extension|legacy [TEST...] the zip, installed into a new user folder
# TEST is a file name without .py (default: every test_*.py). Prints "N passed, N failed"; non-zero
# on a failure. BLENDER picks the binary (default: blender on the PATH).
set -uo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
BLENDER=${BLENDER:-blender}
export SOFTSHADOW_ROOT="$ROOT"

if [ "${1:-}" = "--zip" ]; then
  ZIP=$(cd "$(dirname "${2:?usage: run.sh --zip ZIP extension|legacy}")" && pwd)/$(basename "$2")
  MODE=${3:?usage: run.sh --zip ZIP extension|legacy}
  shift 3
  # shellcheck source=install_zip.sh
  . "$HERE/install_zip.sh"
  install_zip "$ZIP" "$MODE" || exit 1
else
  BUILD_DIR=$(cd "${1:?usage: run.sh BUILD_DIR [TEST...]}" && pwd)
  shift
  export SOFTSHADOW_LIB="$BUILD_DIR/libsoftshadow.so"
  export SOFTSHADOW_ADDON_PATH="$ROOT/blender_addon"
  export SOFTSHADOW_BUILD_DIR="$BUILD_DIR"
fi

if [ $# -gt 0 ]; then
  tests=(); for name in "$@"; do tests+=("$HERE/$name.py"); done
else
  tests=("$HERE"/test_*.py)
fi
LOGS=$(mktemp -d)
passed=0; failed=0
for test in "${tests[@]}"; do
  name=$(basename "$test" .py)
  log="$LOGS/$name.log"
  if timeout 900 "$BLENDER" --background --factory-startup --python-exit-code 1 \
       --python "$test" >"$log" 2>&1 && grep -q "^SOFTSHADOW-TEST-OK" "$log"; then
    passed=$((passed + 1)); echo "PASS $name"
  else
    failed=$((failed + 1)); echo "FAIL $name"
    tail -n 40 "$log" | sed 's/^/    /'
  fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
