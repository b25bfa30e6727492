#!/usr/bin/env bash
# How the one zip is tested in every Blender we support: the host's Blender 3.4, and Debian trixie
# (Blender 4.3) and sid (Blender 5.x LTS) root file systems that hold Blender and GL runtime only.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: tests/matrix/run.sh ZIP
# The root file systems are built once with mmdebstrap and kept in SOFTSHADOW_ROOTFS_CACHE
# (default /var/cache/softshadow/rootfs). They hold none of the project's build dependencies, so
# a library in the zip that is not self-contained fails there. Needs root (chroot, mounts).
# When Debian's archive cannot be reached for a missing root file system, that version is
# reported as SKIPPED loudly and the run goes on; any test failure makes the exit non-zero.
set -uo pipefail
ZIP=$(cd "$(dirname "${1:?usage: run.sh ZIP}")" && pwd)/$(basename "$1")
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
# shellcheck source=rootfs.sh
. "$HERE/rootfs.sh"
SUITES=${SOFTSHADOW_MATRIX_SUITES:-trixie sid}
# Every Blender test but those about the source tree itself (SOFTSHADOW_LIB, package.sh, the
# bench's scripts).
SOURCE_ONLY=" test_register test_package test_scene_export_pure test_error_regions "
TESTS=()
for t in "$ROOT"/tests/blender/test_*.py; do
  name=$(basename "$t" .py)
  [[ "$SOURCE_ONLY" == *" $name "* ]] || TESTS+=("$name")
done

failures=0
skipped=()
banner() { printf '\n==== %s ====\n' "$*"; }

run_suite_in() {  # run_suite_in DIR: the suite against the extension, a short one against the legacy add-on
  local dir=$1 work
  work=$(copy_into "$dir" "$ZIP")
  local zip="$work/$(basename "$ZIP")"
  in_chroot "$dir" env -i PATH=/usr/bin:/bin LANG=C.UTF-8 bash "$work/tests/blender/run.sh" \
    --zip "$zip" extension "${TESTS[@]}" || failures=$((failures + 1))
  in_chroot "$dir" env -i PATH=/usr/bin:/bin LANG=C.UTF-8 bash "$work/tests/blender/run.sh" \
    --zip "$zip" legacy test_install_modes test_render_passes || failures=$((failures + 1))
}

if [ "$(id -u)" != 0 ]; then
  banner "VERSION MATRIX SKIPPED: needs root for chroot and mounts"
  skipped+=("trixie" "sid")
  SUITES=""
fi

banner "host: $(blender --version 2>/dev/null | head -n 1) (legacy add-on)"
bash "$HERE/../blender/run.sh" --zip "$ZIP" legacy "${TESTS[@]}" || failures=$((failures + 1))

for suite in $SUITES; do
  if ! dir=$(rootfs "$suite"); then
    banner "VERSION MATRIX: Debian $suite SKIPPED: cannot build its root file system (is $MIRROR reachable?)"
    skipped+=("$suite")
    continue
  fi
  banner "Debian $suite: $(chroot "$dir" blender --version 2>/dev/null | head -n 1)"
  run_suite_in "$dir"
done

echo
if [ ${#skipped[@]} -gt 0 ]; then
  echo "!!!! VERSION MATRIX INCOMPLETE: not tested in ${skipped[*]} !!!!"
fi
echo "version matrix: $failures failing run(s)"
[ "$failures" -eq 0 ]
