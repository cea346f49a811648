# Sourced by scripts/build.sh and scripts/sanitize.sh: when ccache is installed, sets
# `ccache_args` to the CMake arguments that compile through it, and exports the settings that
# let every clone of attend on this machine share one cache:
#   - the cache lives outside the clone (CCACHE_DIR, default ~/.cache/ccache), so a fresh
#     clone reuses what earlier builds compiled;
#   - paths below the clone are rewritten relative to the build folder (CCACHE_BASEDIR), and
#     the working folder is left out of the hash (CCACHE_NOHASHDIR), so the same source file
#     compiled in another clone is a hit; debug information then names the first clone's
#     paths, which only matters to the sanitizer build's reports (file and line are the same).
# ATTEND_CCACHE=0 turns it off. `ccache -s` shows the hits.
ccache_args=()
if [ "${ATTEND_CCACHE:-1}" != "0" ] && command -v ccache >/dev/null 2>&1; then
  # The settings ride in the launcher, so that `make` run by hand in the build folder uses
  # them too.
  launcher="/usr/bin/env;CCACHE_BASEDIR=$root;CCACHE_NOHASHDIR=1;ccache"
  ccache_args=(-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher" -DCMAKE_C_COMPILER_LAUNCHER="$launcher")
  # Room for the Release and the sanitizer builds of a few clones (the default is 5 GB).
  ccache --max-size=8G >/dev/null
else
  # A build folder configured with ccache before keeps its launcher otherwise.
  ccache_args=(-DCMAKE_CXX_COMPILER_LAUNCHER= -DCMAKE_C_COMPILER_LAUNCHER=)
fi
