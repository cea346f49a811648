#!/usr/bin/env bash
# Per-region disparity of both target methods on the ten Middlebury pairs of the reference data
# (issue 44; docs/STEREO3D.md): `attend disparity --gt --regions 0.01` on each pair, then one
# table row per pair and the totals over the regions of the 2003 pairs (where the defaults
# were chosen) and of the 2005 pairs (held out).
# Usage: scripts/eval_region_disparity.sh [DATA] [ATTEND] [-- --set disparity.KEY=VALUE ...]
set -euo pipefail
data=${1:-$(dirname "$0")/../../shared/data}
attend=${2:-$(dirname "$0")/../build/attend}
shift $(( $# > 2 ? 2 : $# )) || true
[[ "${1:-}" == "--" ]] && shift
extra=("$@")
if [[ ! -d "$data/middlebury" || ! -d "$data/middlebury2005" ]]; then
  echo "eval_region_disparity: no Middlebury pairs under $data (give the data folder)" >&2
  exit 2
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() {  # NAME SET LEFT RIGHT GT SCALE D
  "$attend" disparity "$3" "$4" --out "$out/$1.pfm" --max-disparity "$7" --gt "$5" \
      --gt-scale "$6" --regions 0.01 "${extra[@]}" > "$out/$2-$1.json"
}
m=$data/middlebury
run tsukuba 2003 "$m/tsukuba/im3.png" "$m/tsukuba/im4.png" "$m/tsukuba/disp3.pgm" 16 16
run venus 2003 "$m/venus/im2.png" "$m/venus/im6.png" "$m/venus/disp2.pgm" 8 20
run teddy 2003 "$m/teddy/im2.png" "$m/teddy/im6.png" "$m/teddy/disp2.png" 4 60
run cones 2003 "$m/cones/im2.png" "$m/cones/im6.png" "$m/cones/disp2.png" 4 60
for scene in Art Books Dolls Laundry Moebius Reindeer; do
  s=$data/middlebury2005/$scene
  run "$scene" 2005 "$s/left.png" "$s/right.png" "$s/disp_left.png" 3 80
done
python3 - "$out" <<'PY'
import json, pathlib, sys
rows = {"2003": [], "2005": []}
print("| set | pair | regions | template within 1 px | map within 1 px | template median err | map median err |")
print("|---|---|---:|---:|---:|---:|---:|")
for f in sorted(pathlib.Path(sys.argv[1]).glob("*.json"), key=lambda p: p.name):
    part, pair = f.stem.split("-", 1)
    r = json.loads(f.read_text())["regions"]
    rows[part] += r["per_region"]
    t, m = r["template"], r["map"]
    print(f"| {part} | {pair} | {r['regions']} | {t['within_1px']:.2f} | {m['within_1px']:.2f} | "
          f"{t['median_abs_error_px']:.2f} | {m['median_abs_error_px']:.2f} |")
for part, regions in rows.items():
    for method in ("template", "map"):
        errs = [abs(r[method]["disparity_px"] - r["truth_px"]) if r[method] else r["truth_px"]
                for r in regions]
        within = sum(e <= 1 for e in errs) / len(errs)
        print(f"{part} {method}: {len(errs)} regions, within 1 px {within:.3f}")
PY
