#!/usr/bin/env bash
# How the add-on zip is made: the package, the built library and the libraries it needs beside it;
# one zip that installs as a legacy add-on (3.4+) and as an extension (4.2+).
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: blender_addon/package.sh BUILD_DIR VERSION  ->  dist/softshadow-VERSION.zip
set -euo pipefail
BUILD_DIR=${1:?usage: package.sh BUILD_DIR VERSION}
VERSION=${2:?usage: package.sh BUILD_DIR VERSION}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD_DIR=$(cd "$BUILD_DIR" && pwd)
LIB="$BUILD_DIR/libsoftshadow.so"
if [ ! -e "$LIB" ]; then
  echo "package.sh: $LIB not found (build the 'softshadow' target first)" >&2
  exit 1
fi
STAGE=$(mktemp -d)
trap 'rm -rf "$STAGE"' EXIT
mkdir -p "$STAGE/softshadow/lib"
# Sources only: no caches, no stray libraries from a developer's tree.
(cd "$ROOT/blender_addon/softshadow" && find . -name '__pycache__' -prune -o -type f \
   \( -name '*.py' -o -name '*.toml' \) -print | while read -r f; do
     mkdir -p "$STAGE/softshadow/$(dirname "$f")"; cp "$f" "$STAGE/softshadow/$f"; done)
# The real file under the plain name: ctypes opens lib/libsoftshadow.so; zips keep no symlinks.
cp -L "$LIB" "$STAGE/softshadow/lib/libsoftshadow.so"
strip --strip-unneeded "$STAGE/softshadow/lib/libsoftshadow.so" 2>/dev/null || true
patchelf --set-rpath '$ORIGIN' "$STAGE/softshadow/lib/libsoftshadow.so"
bash "$ROOT/blender_addon/bundle_libs.sh" "$STAGE/softshadow/lib/libsoftshadow.so" "$STAGE/softshadow/lib" >/dev/null
cp "$ROOT/LICENSE" "$STAGE/softshadow/LICENSE"
sed -i "s/^version = \".*\"/version = \"$VERSION\"/" "$STAGE/softshadow/blender_manifest.toml"
IFS=. read -r MAJ MIN PAT <<<"$VERSION"
sed -i "s/\"version\": ([0-9, ]*)/\"version\": (${MAJ:-0}, ${MIN:-0}, ${PAT:-0})/" "$STAGE/softshadow/__init__.py"
DIST=${SOFTSHADOW_DIST:-$ROOT/dist}
mkdir -p "$DIST"
OUT="$(cd "$DIST" && pwd)/softshadow-$VERSION.zip"
rm -f "$OUT"
(cd "$STAGE" && zip -qr -X "$OUT" softshadow)
echo "$OUT"
