#!/usr/bin/env bash
# What one light costs in memory by resolution: the maximum resident set of `softshadow render`
# (/usr/bin/time -v) beside the budget docs/reliability.md states (core/memory_budget.h, read
# from the header so the two cannot drift apart), as a Markdown table on stdout.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: bench/memory_budget.sh CLI WORK_DIR "SIDES" "METHODS"
#   e.g. ... "1024 4096 8192" "shadow_map occlusion_textures auto+refine" (a method, "+refine" for refine=on)
set -euo pipefail
CLI=${1:?usage: memory_budget.sh CLI WORK_DIR SIDES METHODS}
WORK=${2:?}
SIDES=${3:-"1024 4096 8192"}
METHODS=${4:-"shadow_map auto+refine"}
HERE=$(cd "$(dirname "$0")" && pwd)
HEADER="$HERE/../native/src/core/memory_budget.h"
constant() { sed -n "s/^inline constexpr double $1 = \([0-9.e]*\);.*/\1/p" "$HEADER"; }
FIXED=$(constant kBudgetFixedBytes)
PER_GL=$(constant kBudgetBytesPerPixelGl)
PER_AUTO=$(constant kBudgetBytesPerPixelAuto)
PER_CPU=$(constant kBudgetBytesPerPixelCpu)
PER_TRI=$(constant kBudgetBytesPerTriangle)
mkdir -p "$WORK"
SCENE="$WORK/memory_scene.json"
cat > "$SCENE" <<'JSON'
{"format":"softshadow-scene","version":1,
 "camera":{"look_from":[0,-4,6],"look_at":[0,0,0],"fov_y_degrees":45,"far":100,"width":64,"height":64},
 "lights":[{"name":"Key","type":"disk","position":[1,0.5,4],"direction":[0,0,-1],"size":1}],
 "meshes":[{"name":"Ground","primitive":{"type":"plane","size":8}},
           {"name":"Box","primitive":{"type":"box","size":1,"subdivisions":8},"translate":[0,0,1]},
           {"name":"Torus","primitive":{"type":"torus"},"translate":[-1.5,0.5,0.8]}]}
JSON
TRIANGLES=$((2 + 12 * 8 * 8 + 2 * 48 * 12))  # the plane, the box, the torus
echo "| method | pixels | max RSS (MB) | budget (MB) | seconds |"
echo "|---|---|---|---|---|"
for side in $SIDES; do
  for method in $METHODS; do
    case $method in
      auto*) per=$PER_AUTO ;;
      reference) per=$PER_CPU ;;
      *) per=$PER_GL ;;
    esac
    set -- -m "${method%%+*}"
    [ "$method" != "${method%+refine}" ] && set -- "$@" --refine
    /usr/bin/time -v "$CLI" render "$SCENE" "$@" --width "$side" --height "$side" \
      -o "$WORK/memory_$side.exr" > "$WORK/memory_$side.txt" 2> "$WORK/memory_$side.time" ||
      { echo "| $method | ${side}² | failed: $(grep -m1 error "$WORK/memory_$side.time") | | |"; continue; }
    rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$WORK/memory_$side.time")
    secs=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$WORK/memory_$side.time")
    budget=$(python3 -c "print(round(($FIXED + $per * $side * $side + $PER_TRI * $TRIANGLES + 8 * 2048 * 2048) / 1e6))")
    echo "| $method | ${side}² | $((rss / 1000)) | $budget | $secs |"
    rm -f "$WORK/memory_$side.exr"
  done
done
