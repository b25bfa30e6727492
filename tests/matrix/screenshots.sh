#!/usr/bin/env bash
# How the user guide's screenshots are taken in Blender 5.x: the zip installed as an extension in
# the Debian sid root file system, a real window under Xvfb, the pictures copied to docs/images.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: tests/matrix/screenshots.sh ZIP [SUITE]   (SUITE: sid by default; needs root)
set -euo pipefail
ZIP=$(cd "$(dirname "${1:?usage: screenshots.sh ZIP [SUITE]}")" && pwd)/$(basename "$1")
SUITE=${2:-sid}
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
# shellcheck source=rootfs.sh
. "$HERE/rootfs.sh"
dir=$(rootfs "$SUITE")
work=$(copy_into "$dir" "$ZIP")
mkdir -p "$dir$work/shots"
in_chroot "$dir" env -i PATH=/usr/bin:/bin LANG=C.UTF-8 bash -c "
  . $work/tests/blender/install_zip.sh && install_zip $work/$(basename "$ZIP") extension &&
  SOFTSHADOW_SHOTS=$work/shots blender --background --factory-startup --python-exit-code 1 \
    --python $work/tests/blender/make_screenshots.py"
cp "$dir$work/shots/"*.png "$ROOT/docs/images/"
ls "$dir$work/shots"
