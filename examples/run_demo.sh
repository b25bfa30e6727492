#!/usr/bin/env bash
# Renders the built-in example with `reference`, `shadow_map` and every soft method into out/demo.exr with one PNG
# preview per pass, then prints the summary and how far shadow_map is from reference.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: examples/run_demo.sh BUILD_DIR
set -euo pipefail
BUILD_DIR=${1:?usage: examples/run_demo.sh BUILD_DIR}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BIN="$BUILD_DIR/softshadow"
[ -x "$BIN" ] || BIN="$ROOT/$BUILD_DIR/softshadow"
[ -x "$BIN" ] || { echo "run_demo.sh: no softshadow binary in $BUILD_DIR" >&2; exit 1; }
OUT="$ROOT/out"
mkdir -p "$OUT"

echo "== softshadow info"
"$BIN" info || echo "(no GL backend: GL methods will fail)"
echo
echo "== softshadow render examples/scenes/demo.json -m reference,shadow_map,pcss,dbuffer,penumbra_map,occlusion_textures,sweep"
"$BIN" render "$ROOT/examples/scenes/demo.json" -m reference,shadow_map,pcss,dbuffer,penumbra_map,occlusion_textures,sweep \
    -o "$OUT/demo.exr" --png-dir "$OUT"
echo
echo "== softshadow compare out/demo.exr (each method against reference, over the mask)"
"$BIN" compare "$OUT/demo.exr"
