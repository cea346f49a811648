#!/usr/bin/env bash
# Quick start, command 2: install what is missing, build, and run the whole test suite: the C++
# tests (ctest), then the Python module's tests (pytest, python/tests, docs/PYTHON.md).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ATTEND_BUILD_DIR:-$root/build}"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh"
cd "$build"
ctest --output-on-failure --timeout 300 -j"$(nproc)"
"$root/scripts/test_python.sh"
