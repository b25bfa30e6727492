#!/usr/bin/env bash
# Which shared libraries travel with libsoftshadow.so in the add-on, and how they find each other.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: bundle_libs.sh LIBRARY DEST_DIR
# Copies every library LIBRARY needs, directly or through another, into DEST_DIR, except those
# every Linux desktop that runs Blender has (glibc's parts, libstdc++, libgcc_s, the GL loaders),
# and points each copy's RUNPATH at its own folder ($ORIGIN), the way Python wheels are repaired.
# Bundled libraries keep their SONAME: when Blender has already loaded one of the same SONAME
# (libz, libtbb) the process's copy is used, which their stable ABIs allow.
set -euo pipefail
LIB=${1:?usage: bundle_libs.sh LIBRARY DEST_DIR}
DEST=${2:?usage: bundle_libs.sh LIBRARY DEST_DIR}
SYSTEM='^(linux-vdso\.so|ld-linux-x86-64\.so|libc\.so|libm\.so|libdl\.so|libpthread\.so|librt\.so|libstdc\+\+\.so|libgcc_s\.so|libEGL\.so|libGL\.so|libOpenGL\.so|libGLX\.so|libGLdispatch\.so|libOSMesa\.so)'
mkdir -p "$DEST"
# ldd resolves the whole tree the way the loader will; "=> /path" rows are the real files.
ldd "$LIB" | awk '/=> \// {print $1, $3}' | while read -r soname path; do
  if [[ "$soname" =~ $SYSTEM ]]; then continue; fi
  cp -L "$path" "$DEST/$soname"
  chmod u+w "$DEST/$soname"
  strip --strip-unneeded "$DEST/$soname" 2>/dev/null || true
  patchelf --set-rpath '$ORIGIN' "$DEST/$soname"
  echo "$soname"
done
if ldd "$LIB" | grep -q 'not found'; then
  echo "bundle_libs.sh: $LIB has unresolved dependencies:" >&2
  ldd "$LIB" | grep 'not found' >&2
  exit 1
fi
