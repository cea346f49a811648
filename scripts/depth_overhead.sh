#!/usr/bin/env bash
# The whole loop's time a frame with each target's disparity and position on, against off
# (issue 44; docs/STEREO3D.md): `attend run` on SEQ with depth.method off, map and template,
# alternated, REPEATS rounds, one thread, no dumps; prints each run's ms a frame (the summary's
# wall time over its frames) and the medians' ratios to off.
# Usage: scripts/depth_overhead.sh SEQ [REPEATS] [ATTEND] [--set ...]
set -euo pipefail
seq=$1
repeats=${2:-5}
attend=${3:-$(dirname "$0")/../build/attend}
shift $(( $# > 3 ? 3 : $# ))
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for ((r = 0; r < repeats; ++r)); do
  for method in off map template; do
    "$attend" run --sequence "$seq" --out "$out/$method-$r" --quiet --set threads=1 \
        --set output.dump=[] --set depth.method=$method "$@" > /dev/null
  done
done
python3 - "$out" "$repeats" <<'PY'
import json, statistics, sys
out, repeats = sys.argv[1], int(sys.argv[2])
ms = {}
for method in ("off", "map", "template"):
    ms[method] = []
    for r in range(repeats):
        s = json.load(open(f"{out}/{method}-{r}/summary.json"))
        ms[method].append(1000.0 * s["wall_seconds"] / s["frames"])
for method, values in ms.items():
    median = statistics.median(values)
    print(f"{method}: ms a frame {' '.join(f'{v:.2f}' for v in values)}; median {median:.2f}; min {min(values):.2f} (ratio {min(values) / min(ms['off']):.3f}); "
          f"ratio to off {median / statistics.median(ms['off']):.3f}")
PY
