#!/usr/bin/env bash
# Builds attend and its whole test suite with AddressSanitizer (leak checking included) and
# UndefinedBehaviorSanitizer into build-sanitize/ (or $ATTEND_SANITIZE_BUILD_DIR), then runs the
# whole suite. Any sanitizer report fails, in a test itself or in an `attend` it starts.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ATTEND_SANITIZE_BUILD_DIR:-$root/build-sanitize}"

"$root/scripts/install_deps.sh"
# -O1 -g1: -O1 is what the sanitizers' authors advise for speed, and -g1 (line tables only)
# still gives every frame of a report its file and line. Against -O2 -g it halves the compile
# time, which is most of this script's time, for a suite a little slower.
# A unity build (CMake joins up to 16 source files of a target into one translation unit):
# about half the compile time, as OpenCV's and the standard library's headers are parsed once
# per batch instead of once per file; reports still name the original files and lines.
# The Python module is left out (-DATTEND_BUILD_PYTHON=OFF): an instrumented extension needs
# the sanitizer runtime preloaded into the interpreter, whose own allocations LeakSanitizer
# then reports; its tests run in scripts/test.sh.
source "$root/scripts/ccache.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${ccache_args[@]}" \
  -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16 \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DATTEND_SANITIZE=address,undefined \
  -DATTEND_BUILD_PYTHON=OFF >/dev/null
cmake --build "$build" -j"$(nproc)"

# Every sanitizer stops its process at the first report with a failing status, so a report in
# a test fails that test. A report in an `attend` the test starts fails it too, even when the
# test expects `attend` to fail: the test support checks every child's stderr for one
# (tests/support/attend_process.cc). The environment reaches those children. Leaks are checked
# as each process exits; the initialisation-order checks catch a global that reads another
# file's global before that one is constructed.
# intercept_tls_get_addr=0: up to GCC 13 the runtime's __tls_get_addr interceptor takes a dynamic
# TLS block whose address happens to sit at a certain offset in its page for a glibc 2.19 header
# and records a garbage range, and LeakSanitizer's tracer then dies on it at exit ("Tracer caught
# signal 11", "LeakSanitizer has encountered a fatal error"), a failure that reports no leak
# (google/sanitizers issue 1322). Off, dynamic TLS blocks are not scanned as roots; static TLS
# and every stack and global still are.
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:check_initialization_order=1:strict_init_order=1:intercept_tls_get_addr=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# Third-party leaks only, each explained in the file.
export LSAN_OPTIONS="suppressions=$root/sanitizers/lsan.supp:print_suppressions=0"
# OpenCV tries its gPhoto2 camera backend on a video file the others refuse, and libgphoto2's
# USB driver leaks there in a way no suppression can name (sanitizers/lsan.supp says why). No
# test uses a camera, so the backend is off for the run.
export OPENCV_VIDEOIO_PRIORITY_GPHOTO2=0

cd "$build"
# Left out here, and run by scripts/test.sh: the tests whose time is a real service's rather
# than attend's code. The four SweepSlurm tests wait on a Slurm cluster's scheduler (its
# one-minute time limit, its start) for 90-100 s each, sanitized or not, and the two CompareCli
# Chromium tests on a headless browser rendering a page; together about 430 of this pass's
# 2,800 test-seconds, and the C++ they reach (the sweep's Slurm records, the
# report's writer) also runs in tests that stay (SweepCli, SweepRecords, CompareCli).
# A longer timeout than scripts/test.sh's 300 s, as instrumented code runs slower.
ctest --output-on-failure --timeout 900 -j"$(nproc)" -E '^SweepSlurm\.|^CompareCli\..*Chromium$'
echo "[attend] sanitizers: the suite passed with no report (real-service tests: scripts/test.sh)"
