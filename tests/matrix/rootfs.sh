# How the version matrix gets a Debian root file system holding only Blender and GL runtime, and
# runs a command inside it. Sourced by tests/matrix/run.sh and tests/matrix/screenshots.sh.
# SPDX-License-Identifier: GPL-3.0-or-later
CACHE=${SOFTSHADOW_ROOTFS_CACHE:-/var/cache/softshadow/rootfs}
MIRROR=${SOFTSHADOW_DEBIAN_MIRROR:-http://deb.debian.org/debian}
# What a user's machine has: Blender, numpy (Blender's Python needs it), GL runtime, X for the
# windowed tests, unzip. Nothing the library is built with.
PACKAGES=blender,python3-numpy,libegl1,libgl1-mesa-dri,xvfb,xauth,unzip

rootfs() {  # rootfs SUITE -> prints the folder; built when missing or its package list changed
  local suite=$1 dir="$CACHE/$1"
  if [ ! -f "$dir/.softshadow-packages" ] || [ "$(cat "$dir/.softshadow-packages")" != "$PACKAGES" ]; then
    rm -rf "$dir" "$dir.tmp"
    mkdir -p "$CACHE"
    # The archive snapshot's Release files may be past their Valid-Until date.
    if ! mmdebstrap --variant=apt --aptopt='Acquire::Check-Valid-Until "false"' \
         --include="$PACKAGES" "$suite" "$dir.tmp" "$MIRROR" >"$CACHE/$suite.log" 2>&1; then
      tail -n 5 "$CACHE/$suite.log" >&2
      rm -rf "$dir.tmp"
      return 1
    fi
    echo "$PACKAGES" >"$dir.tmp/.softshadow-packages"
    mv "$dir.tmp" "$dir"
  fi
  echo "$dir"
}

in_chroot() {  # in_chroot DIR COMMAND...: /proc, /dev, /sys mounted for the command, then unmounted
  local dir=$1; shift
  local m mounted=()
  for m in proc dev sys; do
    mount --bind "/$m" "$dir/$m" && mounted+=("$dir/$m")
  done
  chroot "$dir" "$@"
  local rc=$?
  for m in "${mounted[@]}"; do umount -l "$m"; done
  return $rc
}

copy_into() {  # copy_into DIR ZIP -> prints the folder inside DIR holding the zip and tests/blender
  local dir=$1 zip=$2 work=/tmp/softshadow-matrix
  rm -rf "${dir:?}$work"; mkdir -p "$dir$work/tests"
  cp "$zip" "$dir$work/"
  cp -r "$ROOT/tests/blender" "$dir$work/tests/"
  echo "$work"
}
