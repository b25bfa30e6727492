#!/usr/bin/env bash
# How much adaptive sampling and GL refinement save against the plain reference on one scene:
# time, shadow rays per pixel and error against a converged truth, in one run.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: bench/adaptive_reference.sh BUILD_DIR [SCENE.json] [SIZE] [TRUTH_SAMPLES]
# Defaults: examples/scenes/demo.json at 512², truth 1024 samples. Writes into BUILD_DIR/bench_adaptive.
set -euo pipefail
BUILD_DIR=$(cd "${1:?usage: adaptive_reference.sh BUILD_DIR [SCENE] [SIZE] [TRUTH_SAMPLES]}" && pwd)
HERE=$(cd "$(dirname "$0")" && pwd)
SCENE=${2:-$HERE/../examples/scenes/demo.json}
SIZE=${3:-512}
TRUTH=${4:-1024}
CLI="$BUILD_DIR/softshadow"
WORK="$BUILD_DIR/bench_adaptive"
[ -x "$CLI" ] || { echo "adaptive_reference: $CLI is missing: build first" >&2; exit 1; }
command -v oiiotool > /dev/null || { echo "adaptive_reference: oiiotool is missing (apt install openimageio-tools)" >&2; exit 1; }
mkdir -p "$WORK"

render() {  # name method [--set ...]...: renders, prints its wall seconds
  local name=$1 method=$2
  shift 2
  "$CLI" render "$SCENE" -m "$method" --width "$SIZE" --height "$SIZE" "$@" -o "$WORK/$name.exr" > "$WORK/$name.txt"
  sed -n 's/.*total \([0-9.]*\) s/\1/p' "$WORK/$name.txt"
}

# Mean of a layer over the image (channel found by name; layers absent give "-").
layer_mean() {  # file layer-suffix
  local file=$1 suffix=$2
  local names avgs
  names=$(oiiotool --info -v "$file" | sed -n 's/.*channel list: //p' | tr -d ' ')
  avgs=$(oiiotool --stats "$file" | sed -n 's/.*Stats Avg: //p' | sed 's/ (float)//')
  python3 - "$names" "$avgs" "$suffix" <<'PY'
import sys
names, avgs, suffix = sys.argv[1].split(","), sys.argv[2].split(), sys.argv[3]
hits = [float(a) for n, a in zip(names, avgs) if n.endswith(suffix + ".V")]
print(hits[0] if hits else "-")
PY
}

rmse() {  # file: RMSE of its V against the truth over the truth's mask
  "$CLI" compare "$1" "$WORK/truth.exr" --json | python3 -c "import json,sys; print('%.4f' % json.load(sys.stdin)[0]['rmse'])"
}

echo "scene $(basename "$SCENE") at ${SIZE}², truth: reference at $TRUTH samples"
render truth reference --samples "$TRUTH" > /dev/null
mask=$(layer_mean "$WORK/truth.exr" "_reference_mask")
echo "| run | seconds | shadow rays per mask pixel | RMSE vs truth |"
echo "|---|---|---|---|"
t=$(render plain reference --no-extra)
echo "| reference, 256 samples | $t | 256 | $(rmse "$WORK/plain.exr") |"
for target in 0.005 0.02; do
  t=$(render "adaptive_$target" reference --set adaptive=on --set error_target=$target)
  rays=$(layer_mean "$WORK/adaptive_$target.exr" "_reference_rays")
  per=$(python3 -c "print('%.1f' % ($rays / $mask))")
  echo "| reference adaptive, error_target $target | $t | $per | $(rmse "$WORK/adaptive_$target.exr") |"
done
t=$(render pcss pcss --no-extra)
echo "| pcss | $t | 0 | $(rmse "$WORK/pcss.exr") |"
t=$(render pcss_refine pcss --refine)
rays=$(layer_mean "$WORK/pcss_refine.exr" "_pcss_rays")
refined=$(layer_mean "$WORK/pcss_refine.exr" "_pcss_refined")
per=$(python3 -c "print('%.1f' % ($rays / $mask))")
share=$(python3 -c "print('%.0f%%' % (100 * $refined / $mask))")
echo "| pcss, refine=on ($share of mask pixels traced) | $t | $per | $(rmse "$WORK/pcss_refine.exr") |"
