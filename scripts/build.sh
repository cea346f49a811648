#!/usr/bin/env bash
# Configures attend in Release into build/ (or $ATTEND_BUILD_DIR) and builds the given targets
# (all when none is given).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ATTEND_BUILD_DIR:-$root/build}"
source "$root/scripts/ccache.sh"
# A unity build (CMake joins up to 16 source files of a target into one translation unit, as
# the sanitizer pass does): a build from scratch took 528 s against 937 s file by file on this
# 2-core machine (docs/PERFORMANCE.md, "CI time"), as OpenCV's and the standard library's
# headers are parsed once per batch. ATTEND_UNITY=0 builds file by file, which rebuilds less
# after an edit of one file.
unity=ON
[ "${ATTEND_UNITY:-1}" = "0" ] && unity=OFF
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "${ccache_args[@]}" \
  -DCMAKE_UNITY_BUILD="$unity" -DCMAKE_UNITY_BUILD_BATCH_SIZE=16 >/dev/null
targets=()
for target in "$@"; do targets+=(--target "$target"); done
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
