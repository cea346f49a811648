#!/usr/bin/env bash
# Checks that two builds of attend give the same records on the three bundled scenes (lab,
# occlusions, crowd): each scene is rendered once, run with both binaries, and the frames.jsonl
# files, without their timings, must be identical byte for byte. The check behind a change that
# must not change behaviour (a refactoring; CONTRIBUTING.md).
#
#   scripts/same_records.sh BEFORE_ATTEND AFTER_ATTEND [--set key=value ...]
#
# e.g. build the base commit in a worktree, or keep a copy of build/attend from before the
# change:  cp build/attend /tmp/attend-before; (change, rebuild);
#          scripts/same_records.sh /tmp/attend-before build/attend
# Extra arguments go to both runs. Exit 0 when every scene's records match, 1 when one differs
# (the first differing line is printed), 2 on a usage error.
set -euo pipefail
if [[ $# -lt 2 || ! -x "$1" || ! -x "$2" ]]; then
  echo "usage: $0 BEFORE_ATTEND AFTER_ATTEND [attend run options]" >&2
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
for scene in lab occlusions crowd; do
  "$after" synth "sequences/$scene.yaml" --out "$work/$scene-seq" > /dev/null
  for which in before after; do
    binary="$before"
    [[ $which == after ]] && binary="$after"
    "$binary" run --sequence "$work/$scene-seq" --out "$work/$scene-$which" --quiet "$@" > /dev/null
    sed -E 's/,"timings_ms":\{[^}]*\}//' "$work/$scene-$which/frames.jsonl" > "$work/$scene-$which.jsonl"
  done
  frames=$(wc -l < "$work/$scene-after.jsonl")
  if cmp -s "$work/$scene-before.jsonl" "$work/$scene-after.jsonl"; then
    echo "$scene: the same records ($frames frames)"
  else
    echo "$scene: the records differ"
    diff "$work/$scene-before.jsonl" "$work/$scene-after.jsonl" > "$work/$scene.diff" || true
    head -4 "$work/$scene.diff" | cut -c1-300
    status=1
  fi
done
exit $status
