#!/usr/bin/env bash
# How the libFuzzer targets are built (Debian's clang-14) and run for a bounded time from
# `make test`: the scene loader and compare's EXR reading, each from its corpus in the repo.
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: tests/fuzz/run.sh BUILD_DIR [SECONDS_PER_TARGET]
# The code under test (io/, core/) is compiled here with coverage and AddressSanitizer; the rest
# of the library comes from BUILD_DIR/libsoftshadow_static.a. New inputs go to a scratch copy
# of the corpus, so the repo's corpus changes only when someone adds to it on purpose.
set -euo pipefail
BUILD=${1:?usage: tests/fuzz/run.sh BUILD_DIR [SECONDS]}
SECONDS_EACH=${2:-45}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(cd "$BUILD" && pwd)
CXX=${FUZZ_CXX:-clang++-14}
OUT="$BUILD/fuzz"
mkdir -p "$OUT"
VERSION=$(sed -n 's/^project.softshadow VERSION \([0-9.]*\).*/\1/p' "$ROOT/CMakeLists.txt")
FLAGS=(-std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
       -DSS_VERSION="\"$VERSION\"" -I"$ROOT/native/src" -I"$ROOT/native/include"
       $(pkg-config --cflags OpenEXR))
LIBS=("$BUILD/libsoftshadow_static.a" -lembree3 $(pkg-config --libs OpenEXR) -ldl -pthread)
CORE=("$ROOT"/native/src/core/{names,scene,light,light_links,camera,mesh,mesh_alpha,scene_range,memory_budget}.cpp)
SCENE=("$ROOT"/native/src/io/{scene_file,scene_file_materials,scene_file_links,json_node,json_reader,input_file,primitives}.cpp)
EXR=("$ROOT"/native/src/io/{exr_file,exr_limits,input_file,atomic_file}.cpp)

build() {  # name sources...
  local name=$1; shift
  # Rebuilt when any source or header of the library, or the target, is newer than it.
  if [ ! -x "$OUT/$name" ] || [ -n "$(find "$ROOT/native/src" "$ROOT/native/include" "$ROOT/tests/fuzz/$name.cpp" \
        "$BUILD/libsoftshadow_static.a" -newer "$OUT/$name" 2>/dev/null | head -1)" ]; then
    echo "fuzz: building $name"
    ccache_cmd=$(command -v ccache || true)
    $ccache_cmd "$CXX" "${FLAGS[@]}" "$ROOT/tests/fuzz/$name.cpp" "$@" "${LIBS[@]}" -o "$OUT/$name"
  fi
}

run() {  # name corpus
  local name=$1 corpus=$2 work="$OUT/corpus_$2"
  rm -rf "$work" && mkdir -p "$work" && cp "$ROOT/tests/fuzz/corpus/$corpus"/* "$work/"
  echo "fuzz: $name for ${SECONDS_EACH}s from tests/fuzz/corpus/$corpus ($(ls "$work" | wc -l) inputs)"
  # Crashes, leaks, timeouts (10 s an input) and allocations over 2 GB fail the run; the
  # reproducer lands in $OUT as crash-*/timeout-*/oom-*.
  (cd "$OUT" && ASAN_OPTIONS=detect_leaks=1 "./$name" "$work" -max_total_time="$SECONDS_EACH" \
      -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -print_final_stats=1 2>&1 | tail -15)
}

build fuzz_scene_loader "${CORE[@]}" "${SCENE[@]}"
build fuzz_exr_read "${CORE[@]}" "${EXR[@]}"
run fuzz_scene_loader scene
run fuzz_exr_read exr
