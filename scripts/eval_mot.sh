#!/usr/bin/env bash
# Runs attend on the MOTChallenge pedestrian sequences of the reference data
# (../shared/data/mot/* and ../shared/data/mot_moving/*, beside the repository) and prints one
# markdown table row a sequence from `attend eval`: the attention and MOTChallenge measures at
# IoU 0.5 (docs/ATTENTION.md, "The MOTChallenge measures") and today's revisits and coverage at
# 0.3.
#
#   scripts/eval_mot.sh [--config FILE] [--only NAME] [--frames FIRST:LAST] [--keep]
#                       [--set key=value]... [--peer [--feature NAME]]
#
# The binary is $ATTEND, or build/attend of the repository. --config defaults to
# configs/mono.yaml (the sequences are monocular); --only runs one sequence (its folder name);
# --frames and every --set go to attend run; --keep keeps the run folders (printed at the end).
# --peer also runs the detector alone (`attend track-detections`, docs/ATTENTION.md, "The
# detector-alone peer") with the same configuration, frames and --set on each sequence, scores
# it the same way and prints it as a second row, "SEQ (detector alone)"; the table then has two
# more columns for both rows, the detector's searched pixels a frame and its milliseconds a
# frame (summary.json's `detectors` block; --feature names the channel, default people).
# Relative model paths resolve in $ATTEND_MODELS, ../shared/data/models beside the repository
# when it is unset.
# Exit 0 when every sequence found was run and scored (none found: a message, still 0), 2 on a
# usage error, and attend's status when a run or its evaluation fails.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
attend="${ATTEND:-$root/build/attend}"
config="$root/configs/mono.yaml"
only=""
keep=false
peer=false
feature=people
run_args=()
usage() {
  echo "usage: $0 [--config FILE] [--only NAME] [--frames FIRST:LAST] [--keep]" \
       "[--set key=value]... [--peer [--feature NAME]]" >&2
  exit 2
}
while [[ $# -gt 0 ]]; do
  case "$1" in
    --config) [[ $# -ge 2 ]] || usage; config="$(realpath "$2")"; shift 2 ;;
    --only) [[ $# -ge 2 ]] || usage; only="$2"; shift 2 ;;
    --frames) [[ $# -ge 2 ]] || usage; run_args+=(--frames "$2"); shift 2 ;;
    --set) [[ $# -ge 2 ]] || usage; run_args+=(--set "$2"); shift 2 ;;
    --keep) keep=true; shift ;;
    --peer) peer=true; shift ;;
    --feature) [[ $# -ge 2 ]] || usage; feature="$2"; shift 2 ;;
    -h|--help) usage ;;
    *) echo "$0: unknown argument '$1'" >&2; usage ;;
  esac
done
if [[ ! -x "$attend" ]]; then
  echo "$0: no attend binary at $attend (build it, or set ATTEND)" >&2
  exit 2
fi
if [[ ! -f "$config" ]]; then
  echo "$0: no configuration file $config" >&2
  exit 2
fi
# Model paths that are not beside the configuration are looked for in $ATTEND_MODELS (SPEC 3.4).
if [[ -z "${ATTEND_MODELS:-}" && -d "$root/../shared/data/models" ]]; then
  ATTEND_MODELS="$(cd "$root/../shared/data/models" && pwd)"
  export ATTEND_MODELS
fi

sequences=()
for group in mot mot_moving; do
  folder="$root/../shared/data/$group"
  if [[ ! -d "$folder" ]]; then
    echo "$0: $folder is absent: its sequences are skipped" >&2
    continue
  fi
  for sequence in "$folder"/*/; do
    sequence="${sequence%/}"
    [[ -f "$sequence/gt/objects.csv" ]] || continue
    [[ -z "$only" || "$(basename "$sequence")" == "$only" ]] || continue
    sequences+=("$sequence")
  done
done
if [[ ${#sequences[@]} -eq 0 ]]; then
  if [[ -n "$only" ]]; then
    echo "$0: no sequence named '$only' with gt/objects.csv in ../shared/data/mot{,_moving}" >&2
    exit 2
  fi
  echo "$0: no MOT sequences found beside the repository (../shared/data/mot, mot_moving):" \
       "nothing to evaluate" >&2
  exit 0
fi

work="$(mktemp -d /tmp/attend_eval_mot.XXXXXX)"
if [[ $keep == false ]]; then trap 'rm -rf "$work"' EXIT; fi

header="| sequence | people | attended whole (0.5) | targets started | ids per attended object |"
header+=" purity | IDF1 | MOTA | MOTP | IDSW | revisits (0.3) | coverage (0.3) |"
rule="|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
if [[ $peer == true ]]; then
  header+=" detector px/frame | detector ms/frame |"
  rule+="---:|---:|"
fi
echo "$header"
echo "$rule"

# One table row from an eval report and its row's label; with --peer, the detector's columns
# from the run's summary.json.
row() {
  python3 - "$1" "$2" "$3" "$peer" "$feature" <<'EOF'
import json
import sys

report_path, label, summary_path, peer, feature = sys.argv[1:6]
report = json.load(open(report_path))
mot = report["mot"]["iou_0.5"]
cells = [
    label,
    str(mot["objects"]),
    f'{mot["objects_attended_whole"]} ({mot["attended_whole_fraction"]:.2f})',
    str(mot["targets_started"]),
    f'{mot["ids_per_attended_object"]:.2f}',
    f'{mot["purity"]:.3f}',
    f'{mot["IDF1"]:.3f}',
    f'{mot["MOTA"]:.3f}',
    f'{mot["MOTP"]:.3f}',
    str(mot["IDSW"]),
    str(report["revisits"]),
    f'{report["coverage"]:.2f}',
]
if peer == "true":
    detector = json.load(open(summary_path)).get("detectors", {}).get(feature)
    if detector is None:
        cells += ["-", "-"]
    else:
        cells += [f'{detector["searched_pixels"]:.0f}', f'{detector["ms"]:.1f}']
print("| " + " | ".join(cells) + " |")
EOF
}

for sequence in "${sequences[@]}"; do
  name="$(basename "$sequence")"
  label="$name"
  peer_label="$name (detector alone)"
  if [[ "$(basename "$(dirname "$sequence")")" == mot_moving ]]; then
    label="$name (moving camera)"
    peer_label="$name (moving camera, detector alone)"
  fi
  run="$work/$name"
  echo "$0: $name: attend run" >&2
  "$attend" run --config "$config" --sequence "$sequence" --out "$run" --overwrite --quiet \
    ${run_args[@]+"${run_args[@]}"} > /dev/null
  "$attend" eval "$run" > "$work/$name.eval.json"
  row "$work/$name.eval.json" "$label" "$run/summary.json"
  if [[ $peer == true ]]; then
    echo "$0: $name: attend track-detections" >&2
    "$attend" track-detections --config "$config" --sequence "$sequence" --feature "$feature" \
      --out "$run.peer" --overwrite --quiet ${run_args[@]+"${run_args[@]}"} > /dev/null
    "$attend" eval "$run.peer" > "$work/$name.peer.eval.json"
    row "$work/$name.peer.eval.json" "$peer_label" "$run.peer/summary.json"
  fi
done
if [[ $keep == true ]]; then echo "$0: runs and reports kept in $work" >&2; fi
