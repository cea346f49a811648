#!/usr/bin/env bash
# Tests scripts/get_models.sh (docs/MODELS.md) without the network: every download comes from a
# file:// mirror named by ATTEND_MODELS_BASE_URL.
#
#   tests/scripts/get_models_test.sh GET_MODELS_SH [MODELS_DIR]
#
# Always: usage errors exit 2; a mirror whose yunet model is a small text file makes
# `--only yunet` exit 1 naming the file and both sums, and leaves nothing in the target folder.
# When MODELS_DIR (the reference data's models folder, ../shared/data/models beside the
# repository) is there: a mirror of it gives every file with its pinned sum; a second run with
# no mirror keeps them all; a file changed in place is downloaded again. Exit 0 when all pass,
# 1 at the first failure, 77 (skipped) when curl is absent.
set -uo pipefail

if [[ $# -lt 1 || ! -f "$1" ]]; then
  echo "usage: $0 GET_MODELS_SH [MODELS_DIR]" >&2
  exit 2
fi
script="$1"
models="${2:-}"
if ! command -v curl >/dev/null 2>&1; then
  echo "SKIP: curl is not installed (scripts/install_deps.sh installs it); file:// mirrors need it"
  exit 77
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
checks=0

fail() {
  echo "FAIL: $*" >&2
  if [[ -f "$work/out" ]]; then
    echo "--- the script printed:" >&2
    cat "$work/out" >&2
  fi
  exit 1
}
# run [args...]: runs the script, its stdout and stderr in $work/out, its status in $status.
run() {
  bash "$script" "$@" >"$work/out" 2>&1
  status=$?
}
expect_status() {
  [[ $status -eq $1 ]] || fail "$2: exit status $status, expected $1"
  checks=$((checks + 1))
}
expect_output() {
  grep -qF -- "$1" "$work/out" || fail "$2: the output does not contain '$1'"
  checks=$((checks + 1))
}
# expect_empty DIR WHAT: DIR holds no file, link or temporary (empty folders are allowed).
expect_empty() {
  local left
  left="$(find "$1" -mindepth 1 ! -type d 2>/dev/null)"
  [[ -z "$left" ]] || fail "$2: files left behind: $left"
  checks=$((checks + 1))
}

# Usage errors: exit 2, and -h prints the usage with status 0.
export ATTEND_MODELS_BASE_URL="file://$work/no-mirror"
run
expect_status 2 "no DIR"
run --only nosuchmodel "$work/usage"
expect_status 2 "--only with an unknown name"
expect_output "nosuchmodel" "--only with an unknown name"
run --no-such-option "$work/usage"
expect_status 2 "an unknown option"
run "$work/usage" "$work/usage2"
expect_status 2 "two folders"
[[ ! -e "$work/usage" ]] || fail "a usage error made the target folder"
run -h
expect_status 0 "-h"
expect_output "ATTEND_MODELS_BASE_URL" "-h"

# --list names the upstream file at its commit, and the mirror's when the base URL is set.
unset ATTEND_MODELS_BASE_URL
run --list --only yunet
expect_status 0 "--list"
expect_output "https://raw.githubusercontent.com/ShiqiYu/libfacedetection.train/0047ac24/onnx/yunet_n_640_640.onnx" "--list"
export ATTEND_MODELS_BASE_URL="file://$work/no-mirror/"
run --list --only yolox
expect_output "file://$work/no-mirror/yolox/yolox_nano.onnx" "--list with a base URL"

# A wrong file in the mirror: exit 1, the file and both sums named, nothing left behind.
fake="$work/fake-mirror"
mkdir -p "$fake/yunet"
echo "not a face detector" >"$fake/yunet/yunet_n_640_640.onnx"
got="$(sha256sum "$fake/yunet/yunet_n_640_640.onnx" | cut -d' ' -f1)"
export ATTEND_MODELS_BASE_URL="file://$fake"
run --only yunet "$work/bad"
expect_status 1 "a mirror with a wrong file"
expect_output "yunet/yunet_n_640_640.onnx" "a mirror with a wrong file"
expect_output "expected: 25a606a145a5b6d7271ae138fbd00eba91dad8b83222ae3f2c7ecd0f4a7b0e31" \
  "a mirror with a wrong file"
expect_output "got:      $got" "a mirror with a wrong file"
expect_output "yunet/LICENSE: download failed" "a mirror without a file"
expect_empty "$work/bad" "a mirror with a wrong file"

if [[ -z "$models" || ! -d "$models" ]]; then
  echo "note: no models folder at '${models:-(none given)}'; the full-mirror checks were not run"
  echo "PASS: $checks checks"
  exit 0
fi
models="$(cd "$models" && pwd -P)"  # the mirror's links point here

# A file:// mirror of the reference models: every file arrives with its pinned sum.
mirror="$work/mirror"
while IFS= read -r -d '' file; do
  rel="${file#"$models"/}"
  mkdir -p "$mirror/$(dirname "$rel")"
  ln -s "$file" "$mirror/$rel"
done < <(find "$models" -mindepth 2 -type f -print0)
export ATTEND_MODELS_BASE_URL="file://$mirror"
run "$work/got"
expect_status 0 "the full mirror"
expect_output "all 10 files present and verified" "the full mirror"
unset ATTEND_MODELS_BASE_URL
bash "$script" --list | while read -r sum rel _; do
  [[ -f "$work/got/$rel" && ! -L "$work/got/$rel" ]] || { echo "missing: $rel"; exit 1; }
  actual="$(sha256sum "$work/got/$rel" | cut -d' ' -f1)"
  [[ "$actual" == "$sum" ]] || { echo "$rel: sum $actual, pinned $sum"; exit 1; }
done >"$work/out" 2>&1 || fail "the files from the full mirror"
checks=$((checks + 1))
stray="$(find "$work/got" -name '.*' ! -type d)"
[[ -z "$stray" ]] || fail "temporaries left after the full mirror: $stray"

# Present and verified files are kept: a second run with no mirror at all succeeds.
export ATTEND_MODELS_BASE_URL="file://$work/no-mirror"
run "$work/got"
expect_status 0 "a second run, every file present"
expect_output "(0 downloaded)" "a second run, every file present"

# A file changed in place is downloaded again from the mirror and replaced.
chmod u+w "$work/got/yunet/LICENSE"
echo "edited" >"$work/got/yunet/LICENSE"
export ATTEND_MODELS_BASE_URL="file://$mirror"
run --only yunet "$work/got"
expect_status 0 "a changed file"
expect_output "yunet/LICENSE: present with another sum" "a changed file"
cmp -s "$work/got/yunet/LICENSE" "$models/yunet/LICENSE" || fail "the changed file was not replaced"
checks=$((checks + 1))

echo "PASS: $checks checks"
