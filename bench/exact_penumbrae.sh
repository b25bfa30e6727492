#!/usr/bin/env bash
# Are exact penumbrae cheaper than Cycles? Adaptive reference and pcss refine=on against Cycles-64
# on the Blender quality scenes at 512² and the large suzannes at 1024², in one run.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: bench/exact_penumbrae.sh BUILD_DIR
#   EXACT_SCENES  scenes at 512² (default: the quality scenes of bench/scenes.py)
#   EXACT_LARGE   scenes at 1024² (default: scaled_4,scaled_5)
#   EXACT_TRUTH / EXACT_TRUTH_LARGE  samples of the converged reference (default 1024 / 512)
# Writes bench/results/exact_penumbrae.md (and .json); EXRs stay in BUILD_DIR/bench_exact.
set -euo pipefail
BUILD_DIR=$(cd "${1:?usage: exact_penumbrae.sh BUILD_DIR}" && pwd)
HERE=$(cd "$(dirname "$0")" && pwd)
CLI="$BUILD_DIR/softshadow"
WORK="$BUILD_DIR/bench_exact"
OUT="$HERE/results"
BLENDER=${BLENDER:-blender}
SMALL=${EXACT_SCENES-convex,concave,overlapping,torus,small_occluder,foliage,curved_receiver}
LARGE=${EXACT_LARGE-scaled_4,scaled_5}
TRUTH=${EXACT_TRUTH:-1024}
TRUTH_LARGE=${EXACT_TRUTH_LARGE:-512}
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
blender_scenes 512 "$SMALL"
blender_scenes 1024 "$LARGE"

# 2. Per scene: the truth, our two exact runs, their errors and shares.
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
  oiiotool "$file" --ch "$channel" "$@" --stats | sed -n 's/.*Stats Avg: \([-0-9.e+]*\).*/\1/p'
}

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
    render "$dir" truth reference --samples "$truth_samples" --no-extra > /dev/null
    oiiotool "$dir/cycles_$CYCLES.exr" --ch R,G --chnames "ViewLayer.${light}_reference.V,ViewLayer.${light}_reference_mask.V" \
      -d float -o "$dir/cycles.named.exr"
    t_adaptive=$(render "$dir" adaptive reference --set adaptive=on)
    t_refine=$(render "$dir" refine pcss --set refine=on)
    mask=$(layer_mean "$dir/adaptive.exr" _mask)
    rays=$(layer_mean "$dir/adaptive.exr" _rays)
    # Pixels past the first round (16 rays): the ones adaptive sampling did not decide at once.
    beyond=$(layer_mean "$dir/adaptive.exr" _rays --subc 16.5 --clamp:min=0 --mulc 1000 --clamp:max=1)
    refined=$(layer_mean "$dir/refine.exr" _refined)
    refine_rays=$(layer_mean "$dir/refine.exr" _rays)
    python3 - "$dir/cycles.json" "$size" "$truth_samples" "$t_adaptive" "$t_refine" "$mask" "$rays" "$beyond" \
      "$refined" "$refine_rays" "$(rmse "$dir/cycles.named.exr" "$dir/truth.exr")" \
      "$(rmse "$dir/adaptive.exr" "$dir/truth.exr")" "$(rmse "$dir/refine.exr" "$dir/truth.exr")" >> "$ROWS" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
(size, truth, t_ad, t_re, mask, rays, beyond, refined, refine_rays,
 e_cy, e_ad, e_re) = sys.argv[2:]
mask = float(mask) or 1.0
print(json.dumps({"scene": c["scene"], "size": int(size), "triangles": c["triangles"], "truth_samples": int(truth),
                  "cycles": {"seconds": c["seconds"], "rmse": float(e_cy)},
                  "adaptive": {"seconds": float(t_ad), "rmse": float(e_ad), "rays_per_mask_pixel": float(rays) / mask,
                               "share_beyond_first_round": float(beyond) / mask},
                  "refine": {"seconds": float(t_re), "rmse": float(e_re), "share_traced": float(refined) / mask,
                             "rays_per_mask_pixel": float(refine_rays) / mask}}))
PY
  done
done

# 3. The table.
python3 - "$ROWS" "$OUT/exact_penumbrae.md" "$OUT/exact_penumbrae.json" "$CYCLES" <<'PY'
import json, sys
rows = [json.loads(line) for line in open(sys.argv[1]) if line.strip()]
cycles = sys.argv[4]
json.dump(rows, open(sys.argv[3], "w"), indent=1)
def verdict(run, c):
    return "yes" if run["rmse"] <= c["rmse"] and run["seconds"] <= c["seconds"] / 5 else "no"
out = ["# Exact penumbrae against Cycles-%s" % cycles, "",
       "bench/exact_penumbrae.sh, one run on this machine (2 shared cores): per scene, Cycles at %s samples" % cycles,
       "(direct light only, as bench/scenes.py renders it; seconds of its shadowed render in Blender) beside",
       "`reference adaptive=on` (default error_target 0.005) and `pcss refine=on` (the CLI's total: render,",
       "BVH build, GL start and EXR write; not process start or scene load). RMSE of V against `reference`",
       "at the truth's sample",
       "count over the truth's mask. Target (issue 18): RMSE at or below Cycles' in at most 1/5 of its time.",
       "Traced: adaptive, the share of mask pixels past the first round of 16 rays; refine, the share of",
       "mask pixels re-traced.", "",
       "| scene | size | triangles | truth spp | Cycles-%s s | Cycles RMSE | adaptive s | RMSE | speed-up | rays/px | traced | target | refine s | RMSE | speed-up | traced | target |" % cycles,
       "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    c, a, f = r["cycles"], r["adaptive"], r["refine"]
    out.append("| %s | %d² | %d | %d | %.2f | %.4f | %.2f | %.4f | %.1f× | %.1f | %.0f%% | %s | %.2f | %.4f | %.1f× | %.0f%% | %s |" % (
        r["scene"], r["size"], r["triangles"], r["truth_samples"], c["seconds"], c["rmse"],
        a["seconds"], a["rmse"], c["seconds"] / a["seconds"], a["rays_per_mask_pixel"], 100 * a["share_beyond_first_round"],
        verdict(a, c), f["seconds"], f["rmse"], c["seconds"] / f["seconds"], 100 * f["share_traced"], verdict(f, c)))
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("\n".join(out))
PY
