#!/usr/bin/env bash
# How the benchmark gets EEVEE Next: bench/eevee_next.py in the version matrix's Debian sid root
# file system (Blender 5.x, tests/matrix/rootfs.sh), on the scene files Blender 3.4 saved.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: bench/eevee_next.sh SCENES_DIR   (root: chroot and bind mounts, in a private mount
# namespace so nothing shows outside this command). Headless GL there is Blender's OpenGL
# backend on Mesa's EGL (llvmpipe on a machine without a GPU). Exit 2: no root or no root file
# system (the run goes on without EEVEE Next and the report says why).
set -euo pipefail
SCENES=$(cd "${1:?usage: eevee_next.sh SCENES_DIR}" && pwd)
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/.." && pwd)
if [ "$(id -u)" != 0 ]; then
  echo "EEVEE Next not measured: bench/eevee_next.sh needs root (chroot, bind mounts)" >&2
  exit 2
fi
if [ -z "${SS_NEXT_IN_NAMESPACE:-}" ]; then
  SS_NEXT_IN_NAMESPACE=1 exec unshare --mount --propagation private bash "$0" "$@"
fi
# shellcheck source=../tests/matrix/rootfs.sh
. "$ROOT/tests/matrix/rootfs.sh"
dir=$(rootfs sid) || { echo "EEVEE Next not measured: no Debian sid root file system (see $CACHE/sid.log)" >&2; exit 2; }
inside=/tmp/softshadow-bench-$$
mkdir -p "$dir$inside/bench" "$dir$inside/scenes"
mount --bind "$HERE" "$dir$inside/bench"
mount --bind "$SCENES" "$dir$inside/scenes"
rc=0
in_chroot "$dir" env -i PATH=/usr/bin:/bin LANG=C.UTF-8 HOME=/tmp \
  BENCH_NEXT_SETTINGS="${BENCH_NEXT_SETTINGS:-default,64j}" BENCH_NEXT_BUDGET_S="${BENCH_NEXT_BUDGET_S:-inf}" \
  blender --background --factory-startup --python-exit-code 1 --python "$inside/bench/eevee_next.py" -- \
  "$inside/scenes" || rc=$?
umount "$dir$inside/bench" "$dir$inside/scenes"
rmdir "$dir$inside/bench" "$dir$inside/scenes" "$dir$inside"
exit $rc
