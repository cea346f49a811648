#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build in Release, and run the attention
# pipeline on the bundled sequence. Prints where the outputs are.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh" attend
cd "$root"
"${ATTEND_BUILD_DIR:-$root/build}/attend" run "$@"
