#!/usr/bin/env bash
# Are exact penumbrae cheaper than Cycles? Adaptive reference and pcss refine=on against Cycles-64
# on the Blender quality scenes at 512² and the large suzannes at 1024², in one run.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: bench/exact_penumbrae.sh BUILD_DIR
#   EXACT_SCENES  scenes at 512² (default: the quality scenes of bench/scenes.py)
#   EXACT_LARGE   scenes at 1024² (default: scaled_4,scaled_5)
#   EXACT_TRUTH / EXACT_TRUTH_LARGE  samples of the converged reference (default 1024 / 512)
#   EXACT_TARGETS error targets of our runs (default "0.01 0.005": the default and a stricter one)
#   EXACT_REUSE=1 keeps the scene files, Cycles images and truths of the last run (ours rerun)
# Writes bench/results/exact_penumbrae.md (and .json); EXRs stay in BUILD_DIR/bench_exact.
set -euo pipefail
BUILD_DIR=$(cd "${1:?usage: exact_penumbrae.sh BUILD_DIR}" && pwd)
HERE=$(cd "$(dirname "$0")" && pwd)
CLI="$BUILD_DIR/softshadow"
WORK="$BUILD_DIR/bench_exact"
OUT="$HERE/results"
BLENDER=${BLENDER:-blender}
SMALL=${EXACT_SCENES-convex,concave,overlapping,torus,small_occluder,foliage,curved_receiver,stepped}
LARGE=${EXACT_LARGE-scaled_4,scaled_5}
TRUTH=${EXACT_TRUTH:-1024}
TRUTH_LARGE=${EXACT_TRUTH_LARGE:-512}
TARGETS=${EXACT_TARGETS:-0.01 0.005}
REUSE=${EXACT_REUSE:-0}
CYCLES=64
export SOFTSHADOW_LIB="$BUILD_DIR/libsoftshadow.so"
for f in "$CLI" "$SOFTSHADOW_LIB"; do
  [ -e "$f" ] || { echo "exact_penumbrae: $f is missing: build first" >&2; exit 1; }
done
command -v oiiotool > /dev/null || { echo "exact_penumbrae: oiiotool is missing (apt install openimageio-tools)" >&2; exit 1; }
mkdir -p "$WORK" "$OUT"

# 1. Scene files and Cycles-64 per size.
blender_scenes() {  # size names
  [ -n "$2" ] || return 0
  "$BLENDER" --background --factory-startup --python-exit-code 1 --python "$HERE/exact_penumbrae_blender.py" -- \
    "$WORK/$1" "$1" "$CYCLES" "$2" > "$WORK/blender_$1.log" 2>&1 || { tail -n 40 "$WORK/blender_$1.log"; exit 1; }
  grep -q EXACT-BLENDER-OK "$WORK/blender_$1.log" || { tail -n 40 "$WORK/blender_$1.log"; exit 1; }
  grep '^EXACT ' "$WORK/blender_$1.log"
}
if [ "$REUSE" != 1 ]; then
  rm -rf "$WORK/512" "$WORK/1024"
  blender_scenes 512 "$SMALL"
  blender_scenes 1024 "$LARGE"
fi

# 2. Per scene: the truth, our exact runs, their errors and shares.
render() {  # dir name method [args...]: renders dir/name.exr, prints the CLI's total seconds
  local dir=$1 name=$2 method=$3
  shift 3
  "$CLI" render "$dir/scene.json" -m "$method" "$@" -o "$dir/$name.exr" > "$dir/$name.txt"
  sed -n 's/.*total \([0-9.]*\) s/\1/p' "$dir/$name.txt"
}
rmse() {  # file truth
  "$CLI" compare "$1" "$2" --json | python3 -c "import json,sys; print(json.load(sys.stdin)[0]['rmse'])"
}
# Mean over the image of the layer whose channel name ends in SUFFIX.V, after an optional
# oiiotool op chain (e.g. a threshold); "0" where the layer is absent.
layer_mean() {  # file suffix [ops...]
  local file=$1 suffix=$2 channel
  shift 2
  channel=$(oiiotool --info -v "$file" | sed -n 's/.*channel list: //p' | tr -d ' ' | tr ',' '\n' |
    grep -E "_[a-z_]+${suffix}\.V$" | head -n 1 || true)
  [ -n "$channel" ] || { echo 0; return; }
  oiiotool "$file" --ch "$channel" "$@" --printstats | sed -n 's/.*Stats Avg: \([-0-9.e+]*\).*/\1/p'
}
row() {  # dir size truth_samples run_label seconds file share rays_per_pixel
  python3 - "$1/cycles.json" "$2" "$3" "$4" "$5" "$(rmse "$6" "$1/truth.exr")" "$7" "$8" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
size, truth, run, seconds, rmse, share, rays = sys.argv[2:]
print(json.dumps({"scene": c["scene"], "size": int(size), "triangles": c["triangles"], "truth_samples": int(truth),
                  "cycles_seconds": c["seconds"], "run": run, "seconds": float(seconds), "rmse": float(rmse),
                  "traced_share": float(share), "rays_per_mask_pixel": float(rays)}))
PY
}
ratio() { python3 -c "import sys; a, b = map(float, sys.argv[1:]); print(a / b if b > 0 else 0.0)" "$1" "$2"; }

ROWS="$WORK/rows.jsonl"
: > "$ROWS"
for size in 512 1024; do
  [ -d "$WORK/$size" ] || continue
  truth_samples=$TRUTH
  [ "$size" = 1024 ] && truth_samples=$TRUTH_LARGE
  for dir in "$WORK/$size"/*/; do
    dir=${dir%/}
    name=$(basename "$dir")
    echo "exact_penumbrae: $name at ${size}²" >&2
    light=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['lights'][0]['name'].replace('.', '_').replace(' ', '_'))" "$dir/scene.json")
    if [ "$REUSE" != 1 ] || [ ! -e "$dir/truth.exr" ]; then
      render "$dir" truth reference --samples "$truth_samples" --no-extra > /dev/null
      oiiotool "$dir/cycles_$CYCLES.exr" --ch R,G --chnames "ViewLayer.${light}_reference.V,ViewLayer.${light}_reference_mask.V" \
        -d float -o "$dir/cycles.named.exr"
    fi
    row "$dir" "$size" "$truth_samples" "Cycles-$CYCLES" "$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['seconds'])" "$dir/cycles.json")" \
      "$dir/cycles.named.exr" 1 "$CYCLES" >> "$ROWS"
    for target in $TARGETS; do
      t=$(render "$dir" "adaptive_$target" reference --set adaptive=on --set error_target="$target")
      f="$dir/adaptive_$target.exr"
      mask=$(layer_mean "$f" _mask)
      # Traced: the mask pixels past the first round of 16 rays (not decided at once).
      row "$dir" "$size" "$truth_samples" "reference adaptive, error_target $target" "$t" "$f" \
        "$(ratio "$(layer_mean "$f" _rays --subc 16.5 --clamp:min=0 --mulc 1000 --clamp:max=1)" "$mask")" \
        "$(ratio "$(layer_mean "$f" _rays)" "$mask")" >> "$ROWS"
      t=$(render "$dir" "refine_$target" pcss --refine --set error_target="$target")
      f="$dir/refine_$target.exr"
      row "$dir" "$size" "$truth_samples" "pcss refine=on, error_target $target" "$t" "$f" \
        "$(ratio "$(layer_mean "$f" _refined)" "$mask")" "$(ratio "$(layer_mean "$f" _rays)" "$mask")" >> "$ROWS"
    done
  done
done

# 3. The table (the commit our runs were built from goes in its header).
python3 "$HERE/exact_penumbrae_table.py" "$ROWS" "$OUT/exact_penumbrae.md" "$OUT/exact_penumbrae.json" "$CYCLES" \
  "$(git -C "$HERE" rev-parse --short HEAD 2> /dev/null || echo unknown)"
