#!/usr/bin/env bash
# Runs the Python module's tests (python/tests) with pytest against the build in build/ (or
# $ATTEND_BUILD_DIR): the interpreter the module was built for, the package from the build
# tree, and the `attend` program of the same build. Extra arguments go to pytest
# (e.g. -k records, -x). scripts/test.sh runs it after the C++ tests.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "${ATTEND_BUILD_DIR:-$root/build}" && pwd)"
cache="$build/CMakeCache.txt"
if grep -q '^ATTEND_BUILD_PYTHON:BOOL=OFF' "$cache"; then
  # The dataset converter (scripts/convert_fixations.py) needs no module: its tests still run.
  echo "[attend] the module's tests are skipped: this build has -DATTEND_BUILD_PYTHON=OFF"
  export ATTEND_BINARY="$build/attend" ATTEND_BUILD_DIR="$build" PYTHONDONTWRITEBYTECODE=1
  # Debian's interpreter, which has the numpy and scipy of install_deps.sh.
  python="$(command -v /usr/bin/python3 || command -v python3)"
  exec "$python" -m pytest -p no:cacheprovider -q "$root/python/tests/test_convert_fixations.py" "$@"
fi
python="$(sed -n 's/^Python_EXECUTABLE:[A-Z]*=//p' "$cache")"
python="${python:-python3}"
export PYTHONPATH="$build/python${PYTHONPATH:+:$PYTHONPATH}"
export ATTEND_BINARY="$build/attend" ATTEND_BUILD_DIR="$build" ATTEND_HOME="$root"
# No cache folder in the source tree; bytecode of the tests is not kept either.
export PYTHONDONTWRITEBYTECODE=1
"$python" -m pytest -p no:cacheprovider -q "$root/python/tests" "$@"
