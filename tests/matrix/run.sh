#!/usr/bin/env bash
# How the one zip is tested in every Blender we support: the host's Blender 3.4, Debian trixie
# (Blender 4.3) and sid (Blender 5.x LTS) root file systems that hold Blender and GL runtime only,
# and the 4.2 LTS and 4.5 LTS releases as PyPI's `bpy` modules (tests/matrix/bpy.sh).
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: tests/matrix/run.sh ZIP
# The root file systems are built once with mmdebstrap and kept in SOFTSHADOW_ROOTFS_CACHE
# (default /var/cache/softshadow/rootfs). They hold none of the project's build dependencies, so
# a library in the zip that is not self-contained fails there. Needs root (chroot, mounts).
# The bpy wheels are installed once per version (SOFTSHADOW_BPY_VERSIONS, exact releases) into
# virtual environments kept in SOFTSHADOW_BPY_CACHE (default ~/.cache/softshadow/bpy-X.Y).
# Blender as a module is the same Blender without its program: tests/matrix/bpy_blender.py gives
# the tests the command line they start child Blenders with (how it differs is said there); it
# has no window, so the windowed tests (WINDOWED) run only in the Debian programs.
# A version that cannot be had (Debian's archive or PyPI unreachable, no Python 3.11) is
# reported as SKIPPED loudly and the run goes on; any test failure makes the exit non-zero.
set -uo pipefail
ZIP=$(cd "$(dirname "${1:?usage: run.sh ZIP}")" && pwd)/$(basename "$1")
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
# shellcheck source=rootfs.sh
. "$HERE/rootfs.sh"
# shellcheck source=bpy.sh
. "$HERE/bpy.sh"
SUITES=${SOFTSHADOW_MATRIX_SUITES:-trixie sid}
# Every Blender test but those about the source tree itself (SOFTSHADOW_LIB, package.sh, the
# add-on's modules imported from the source tree, the CLI beside the library, the bench's scripts).
SOURCE_ONLY=" test_register test_package test_scene_export_pure test_framing_pure test_cli_export_parity test_error_regions "
# SOFTSHADOW_MATRIX_TESTS (test names) runs only those, everywhere.
TESTS=()
for t in "$ROOT"/tests/blender/test_*.py; do
  name=$(basename "$t" .py)
  [ -z "${SOFTSHADOW_MATRIX_TESTS:-}" ] || [[ " $SOFTSHADOW_MATRIX_TESTS " == *" $name "* ]] || continue
  [[ "$SOURCE_ONLY" == *" $name "* ]] || TESTS+=("$name")
done

WINDOWED=" test_gui_render test_viewport_preview "
BPY_TESTS=()
for name in "${TESTS[@]}"; do
  [[ "$WINDOWED" == *" $name "* ]] || BPY_TESTS+=("$name")
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

for version in $BPY_VERSIONS; do
  if ! bin=$(bpy_blender "$version"); then
    banner "VERSION MATRIX: Blender $version (bpy module) SKIPPED: cannot install bpy==$version (is PyPI reachable? see $BPY_CACHE/bpy-$version.log)"
    skipped+=("bpy-$version")
    continue
  fi
  banner "bpy module: $("$bin" --version 2>/dev/null | head -n 1) (windowless:${WINDOWED}run in the programs only)"
  BLENDER="$bin" bash "$HERE/../blender/run.sh" --zip "$ZIP" extension "${BPY_TESTS[@]}" || failures=$((failures + 1))
  BLENDER="$bin" bash "$HERE/../blender/run.sh" --zip "$ZIP" legacy test_install_modes test_render_passes \
    || failures=$((failures + 1))
done

echo
if [ ${#skipped[@]} -gt 0 ]; then
  echo "!!!! VERSION MATRIX INCOMPLETE: not tested in ${skipped[*]} !!!!"
fi
echo "version matrix: $failures failing run(s)"
[ "$failures" -eq 0 ]
