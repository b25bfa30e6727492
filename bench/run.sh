#!/usr/bin/env bash
# What `make bench` runs: per-stage native timings, the Blender scenes with EEVEE, EEVEE Next and
# Cycles, our methods on the same scene files, errors against a converged reference, and
# bench/results/.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: bench/run.sh BUILD_DIR    BENCH_QUICK=1: a tiny subset (smoke test, a minute or two).
# Every figure in bench/results/ comes from this one run. Big intermediates (EXR) stay in
# BUILD_DIR/bench_work; the results folder gets JSON, Markdown, SVG and small PNGs only.
set -euo pipefail
BUILD_DIR=$(cd "${1:?usage: run.sh BUILD_DIR}" && pwd)
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/.." && pwd)
QUICK=${BENCH_QUICK:-0}
CLI="$BUILD_DIR/softshadow"
BENCH="$BUILD_DIR/softshadow_bench"
OUT="$HERE/results"
WORK="$BUILD_DIR/bench_work"
# The Blender scenes at the size users render, 512² (the triangle-count series at 256x192,
# bench/scenes.py SCALED_SIZE); the native per-stage tables at 512² and 1024². Truth:
# `reference` at TRUTH_SAMPLES light samples per pixel.
WIDTH=512 HEIGHT=512 TRUTH_SAMPLES=1024
if [ "$QUICK" = 1 ]; then WIDTH=128 HEIGHT=128 TRUTH_SAMPLES=256; fi
BLENDER=${BLENDER:-blender}
export SOFTSHADOW_LIB="$BUILD_DIR/libsoftshadow.so" SOFTSHADOW_BUILD="$BUILD_DIR"

for f in "$CLI" "$BENCH" "$SOFTSHADOW_LIB"; do
  [ -e "$f" ] || { echo "bench: $f is missing: build first (make build)" >&2; exit 1; }
done
rm -rf "$WORK" && mkdir -p "$WORK" "$OUT"
rm -f "$OUT"/*.png "$OUT"/*.svg "$OUT"/*.json "$OUT"/*.md
t_start=$(date +%s)
# The machine's load beside the times: the report prints it (start and end of the run).
uptime > "$WORK/load.txt"
log() { echo "[bench $(( $(date +%s) - t_start ))s] $*"; }

# 1. Native per-stage timings (example scene and a 100k torus at 512² and 1024²), plus the
#    method engineers' own stage benchmarks.
if [ "$QUICK" = 1 ]; then FILTER='BM_Foundation/scene:0/res:512/'; else FILTER='BM_Foundation|BM_PenumbraMap|BM_Occlusion|BM_Dbuffer|BM_Sweep'; fi
log "native stage timings ($FILTER)"
"$BENCH" --benchmark_filter="$FILTER" --benchmark_out="$OUT/foundation.json" \
  --benchmark_out_format=json > "$WORK/foundation.txt" 2>&1 || { tail -n 30 "$WORK/foundation.txt"; exit 1; }

# 2. The Blender scenes: scene files, EEVEE and Cycles visibility, their render times.
log "Blender: scenes, EEVEE, Cycles at ${WIDTH}x${HEIGHT}"
"$BLENDER" --background --factory-startup --python-exit-code 1 --python "$HERE/scenes.py" -- \
  "$WORK/scenes" "$WIDTH" "$HEIGHT" "$QUICK" > "$WORK/blender.log" 2>&1 || { tail -n 40 "$WORK/blender.log"; exit 1; }
grep -q BENCH-SCENES-OK "$WORK/blender.log" || { tail -n 40 "$WORK/blender.log"; exit 1; }
grep '^BENCH ' "$WORK/blender.log" || true

# 2a. EEVEE Next (Blender 5.x in the version matrix's Debian sid root file system) on the scene
#     files 3.4 saved, in the background: it takes longer than steps 3-4d and needs only the
#     scenes, so its renders overlap ours (both are on the load line the report prints). Step 5
#     waits for it.
if [ "$QUICK" = 1 ]; then NEXT_SETTINGS=default; else NEXT_SETTINGS=${BENCH_NEXT_SETTINGS:-default,64j}; fi
log "EEVEE Next in Blender 5.x ($NEXT_SETTINGS), in the background"
BENCH_NEXT_SETTINGS="$NEXT_SETTINGS" bash "$HERE/eevee_next.sh" "$WORK/scenes" > "$WORK/eevee_next.log" 2>&1 &
next_pid=$!

# 3. Per scene: the converged truth, `reference` at its default samples (timed by the CLI),
#    the receiver mask.
SCENE_LIST=""
for dir in "$WORK"/scenes/*/; do
  name=$(basename "$dir")
  light=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['lights'][0]['name'].replace('.', '_').replace(' ', '_'))" "$dir/scene.json")
  log "$name: reference truth ($TRUTH_SAMPLES samples) and default reference"
  "$CLI" render "$dir/scene.json" -m reference --samples "$TRUTH_SAMPLES" --no-extra -o "$dir/truth.exr" > "$dir/truth.txt"
  "$CLI" render "$dir/scene.json" -m reference --no-extra -o "$dir/reference.exr" > "$dir/reference.txt"
  # The receiver mask: receiver objects (bench/scenes.py RECEIVERS) the light reaches, as a pass
  # of a copy of the truth, for `compare --mask receivers`.
  oiiotool "$dir/truth.exr" --ch "ViewLayer.${light}_reference_mask.V" "$dir/receivers.exr" --ch R --mul \
    --chnames "ViewLayer.receivers.V" -d float -o "$dir/receiver_mask.exr"
  oiiotool "$dir/truth.exr" "$dir/receiver_mask.exr" --chappend -o "$dir/truth_receivers.exr"
  SCENE_LIST+="${SCENE_LIST:+;}$name=$dir/scene.json"
done

# 4. Our GL methods on the same scene files: per-stage times and their images.
log "our methods on the Blender scenes"
SS_BENCH_SCENES="$SCENE_LIST" SS_BENCH_OUT="$WORK/ours" "$BENCH" --benchmark_filter='BM_SceneFile' \
  --benchmark_out="$OUT/scene_files.json" --benchmark_out_format=json > "$WORK/scene_files.txt" 2>&1 ||
  { tail -n 30 "$WORK/scene_files.txt"; exit 1; }

# 4a. `auto` as users get it: the CLI on each scene file (it renders every candidate and keeps the
#     one with the least error on its sparse check); its time, the method it took and its estimate;
#     the preview's (GL only) and a final render's (refine=on).
log "auto through the CLI"
for dir in "$WORK"/scenes/*/; do
  name=$(basename "$dir")
  mkdir -p "$WORK/ours/$name"
  "$CLI" render "$dir/scene.json" -m auto --no-extra -o "$WORK/ours/$name/auto.exr" > "$WORK/ours/$name/auto.txt" ||
    echo "auto failed on $name"
  # The method auto took, alone through the same path: auto's cost against it.
  used=$(awk '$2 == "auto" {print $3}' "$WORK/ours/$name/auto.txt")
  [ -n "$used" ] && "$CLI" render "$dir/scene.json" -m "$used" --no-extra -o "$WORK/ours/$name/picked.exr" \
    > "$WORK/ours/$name/picked.txt" && rm -f "$WORK/ours/$name/picked.exr"
  # Issue 18's exact penumbrae: the adaptive reference, and auto's pick refined where it is
  # uncertain; their "rays" / "refined" layers give the share of pixels traced.
  "$CLI" render "$dir/scene.json" -m reference --set adaptive=on -o "$WORK/ours/$name/reference-adaptive.exr" \
    > "$WORK/ours/$name/reference-adaptive.txt" || echo "adaptive reference failed on $name"
  # auto as a final render gets it (the add-on's Refine Final Renders, on by default), and the
  # method it took refined alone, for the time ratio.
  "$CLI" render "$dir/scene.json" -m auto --refine -o "$WORK/ours/$name/auto-refine.exr" \
    > "$WORK/ours/$name/auto-refine.txt" || echo "auto refine=on failed on $name"
  used=$(awk '$2 == "auto" {print $3}' "$WORK/ours/$name/auto-refine.txt")
  [ -n "$used" ] && "$CLI" render "$dir/scene.json" -m "$used" --refine --no-extra \
    -o "$WORK/ours/$name/picked-refine.exr" > "$WORK/ours/$name/picked-refine.txt" &&
    rm -f "$WORK/ours/$name/picked-refine.exr"
  python3 "$HERE/traced_share.py" "$WORK/ours/$name" > "$WORK/ours/$name/traced.json" || echo "traced share failed on $name"
done

# 4b. Memory against the light count (docs/reliability.md): shadow_map on a ring of N lights,
#     the maximum resident set of the whole `softshadow render`.
log "memory with many lights"
if [ "$QUICK" = 1 ]; then COUNTS="50 200"; else COUNTS="50 500 2000"; fi
{
  echo "# Memory against the light count"
  echo
  echo "\`softshadow render -m shadow_map --no-extra\` on a ring of disk lights (bench/many_lights.py, 256x192,"
  echo "2048² shadow maps), maximum resident set from \`/usr/bin/time -v\`."
  echo
  echo "| lights | passes | max RSS (MB) | seconds |"
  echo "|---|---|---|---|"
  for n in $COUNTS; do
    python3 "$HERE/many_lights.py" "$n" "$WORK/lights_$n.json"
    /usr/bin/time -v "$CLI" render "$WORK/lights_$n.json" -m shadow_map --no-extra -o "$WORK/lights_$n.exr" \
      > "$WORK/lights_$n.txt" 2> "$WORK/lights_$n.time"
    rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$WORK/lights_$n.time")
    secs=$(sed -n 's/.*total \([0-9.]*\) s/\1/p' "$WORK/lights_$n.txt")
    echo "| $n | $((2 * n)) | $((rss / 1024)) | $secs |"
  done
  echo
  echo "# Memory against the resolution"
  echo
  echo "One light over a plane, a box and a torus (bench/memory_budget.sh), maximum resident set of"
  echo "\`softshadow render\` beside the budget of docs/reliability.md (core/memory_budget.h)."
  echo
  if [ "$QUICK" = 1 ]; then SIDES="1024"; else SIDES="1024 4096 8192"; fi
  bash "$HERE/memory_budget.sh" "$CLI" "$WORK/memory" "$SIDES" "shadow_map occlusion_textures auto+refine"
} > "$OUT/memory.md"
cat "$OUT/memory.md"

# 4c. The warm path (docs/architecture.md, the caches): render_passes per GL method on the second
#     frame of an animation where one object moved, stage by stage, on 110k and ~1M triangles; the
#     preview's edit-to-overlay latency (median, 95th percentile) over an animated edit sequence.
log "the warm path: render_passes and the preview after a move"
if [ "$QUICK" = 1 ]; then WARM_ARGS="256 2 1"; else WARM_ARGS="1024 5 1,9"; fi
# shellcheck disable=SC2086  # WARM_ARGS is three words
SOFTSHADOW_ADDON_PATH="$ROOT/blender_addon" "$BLENDER" --background --factory-startup --python-exit-code 1 \
  --python "$HERE/warm_render_passes.py" -- "$OUT/warm_render_passes.md" $WARM_ARGS > "$WORK/warm.log" 2>&1 ||
  { tail -n 40 "$WORK/warm.log"; exit 1; }
grep -q BENCH-WARM-OK "$WORK/warm.log" || { tail -n 40 "$WORK/warm.log"; exit 1; }
cat "$OUT/warm_render_passes.md"

# 4d. Exact penumbrae (adaptive reference, pcss refine=on) against Cycles-64 at 512² and on the
#     large suzannes at 1024²: its own script and table (bench/results/exact_penumbrae.md).
[ "$QUICK" = 1 ] || { log "exact penumbrae against Cycles-64"; bash "$HERE/exact_penumbrae.sh" "$BUILD_DIR"; }

# 5. Errors against the truth, and image strips (method | truth | 4 x |error|).
log "waiting for EEVEE Next"
next_rc=0
wait "$next_pid" || next_rc=$?
grep '^BENCH \|EEVEE Next not measured' "$WORK/eevee_next.log" || true
[ "$next_rc" = 0 ] || { tail -n 20 "$WORK/eevee_next.log"; echo "EEVEE Next failed (exit $next_rc): the report says so"; }
echo "$next_rc" > "$WORK/eevee_next.rc"
log "errors and image strips"
for dir in "$WORK"/scenes/*/; do
  name=$(basename "$dir")
  light=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['lights'][0]['name'].replace('.', '_').replace(' ', '_'))" "$dir/scene.json")
  for f in "$dir"/eevee_*.exr "$dir"/cycles_*.exr; do
    [ -e "$f" ] || continue
    case "$f" in *.named.exr) continue ;; esac
    # A Blender file's passes carry the truth's names: compare pairs passes by name.
    oiiotool "$f" --ch R,G --chnames "ViewLayer.${light}_reference.V,ViewLayer.${light}_reference_mask.V" \
      -d float -o "${f%.exr}.named.exr"
  done
  mkdir -p "$WORK/errors/$name"
  candidates=("$dir/reference.exr")
  for f in "$WORK/ours/$name"/*.exr "$dir"/eevee_*.named.exr "$dir"/cycles_*.named.exr; do
    [ -e "$f" ] && candidates+=("$f")
  done
  for f in "${candidates[@]}"; do
    key=$(basename "$f" .exr); key=${key%.named}
    # Over every pixel the light reaches (the truth's mask), whatever the method's own mask: a
    # composite multiplies by V everywhere, and auto's estimate is over the same pixels.
    "$CLI" compare "$f" "$dir/truth.exr" --mask "${light}_reference_mask" --json > "$WORK/errors/$name/$key.json" \
      2>"$WORK/errors/$name/$key.err" ||
      echo "compare failed for $name/$key: $(cat "$WORK/errors/$name/$key.err")"
    "$CLI" compare "$f" "$dir/truth_receivers.exr" --mask receivers --json > "$WORK/errors/$name/$key.receivers.json" \
      2>"$WORK/errors/$name/$key.receivers.err" ||
      echo "compare (receivers) failed for $name/$key: $(cat "$WORK/errors/$name/$key.receivers.err")"
  done
done
python3 "$HERE/strips.py" "$WORK" "$OUT" || echo "image strips failed (see above)"

# 6. The report.
log "report"
uptime >> "$WORK/load.txt"
python3 "$HERE/report.py" "$WORK" "$OUT" "$WIDTH" "$HEIGHT" "$TRUTH_SAMPLES" "$QUICK"
log "done: $OUT/report.md, $OUT/foundation.md"
