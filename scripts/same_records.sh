#!/usr/bin/env bash
# Checks that two builds of attend give the same records on the three bundled scenes (lab,
# occlusions, crowd): each scene is rendered once, run with both binaries, and the frames.jsonl
# files, without their timings, must be identical byte for byte. The check behind a change that
# must not change behaviour (a refactoring; CONTRIBUTING.md).
#
#   scripts/same_records.sh [--real] BEFORE_ATTEND AFTER_ATTEND [--set key=value ...]
#
# --real also compares two real sequences of the reference data beside the repository, when it
# is there (a message, and no failure, when it is not): ../shared/data/mot/TUD-Campus with
# configs/mono.yaml and ../shared/data/euroc_v1_01 with the default configuration.
#
# e.g. build the base commit in a worktree, or keep a copy of build/attend from before the
# change:  cp build/attend /tmp/attend-before; (change, rebuild);
#          scripts/same_records.sh /tmp/attend-before build/attend
# Extra arguments go to both runs. Exit 0 when every scene's records match, 1 when one differs
# (the first differing line is printed), 2 on a usage error.
set -euo pipefail
real=false
if [[ $# -ge 1 && $1 == --real ]]; then
  real=true
  shift
fi
if [[ $# -lt 2 || ! -x "$1" || ! -x "$2" ]]; then
  echo "usage: $0 [--real] BEFORE_ATTEND AFTER_ATTEND [attend run options]" >&2
  exit 2
fi
before="$(realpath "$1")"
after="$(realpath "$2")"
shift 2
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$root"
status=0
# compare NAME SEQUENCE [run options]: runs both binaries on SEQUENCE, compares the records.
compare() {
  local name="$1" sequence="$2"
  shift 2
  for which in before after; do
    binary="$before"
    [[ $which == after ]] && binary="$after"
    "$binary" run --sequence "$sequence" --out "$work/$name-$which" --quiet "$@" > /dev/null
    sed -E 's/,"timings_ms":\{[^}]*\}//' "$work/$name-$which/frames.jsonl" > "$work/$name-$which.jsonl"
  done
  frames=$(wc -l < "$work/$name-after.jsonl")
  if cmp -s "$work/$name-before.jsonl" "$work/$name-after.jsonl"; then
    echo "$name: the same records ($frames frames)"
  else
    echo "$name: the records differ"
    diff "$work/$name-before.jsonl" "$work/$name-after.jsonl" > "$work/$name.diff" || true
    head -4 "$work/$name.diff" | cut -c1-300
    status=1
  fi
}
for scene in lab occlusions crowd; do
  "$after" synth "sequences/$scene.yaml" --out "$work/$scene-seq" > /dev/null
  compare "$scene" "$work/$scene-seq" "$@"
done
if [[ $real == true ]]; then
  data="$root/../shared/data"
  if [[ -d "$data/mot/TUD-Campus" ]]; then
    compare TUD-Campus "$data/mot/TUD-Campus" --config configs/mono.yaml "$@"
  else
    echo "TUD-Campus: $data/mot/TUD-Campus is absent: not compared"
  fi
  if [[ -d "$data/euroc_v1_01" ]]; then
    compare EuRoC "$data/euroc_v1_01" "$@"
  else
    echo "EuRoC: $data/euroc_v1_01 is absent: not compared"
  fi
fi
exit $status
