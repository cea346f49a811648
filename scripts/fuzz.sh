#!/usr/bin/env bash
# Fuzzing (docs/FUZZING.md). Builds the libFuzzer targets of fuzz/ in build-fuzz/ (clang,
# AddressSanitizer and UBSan) when needed, then either
#   bash scripts/fuzz.sh [TARGET...] [--seconds N]
#     runs each target (all when none is named) for N seconds (600 by default) on a scratch copy
#     of its seeds (build-fuzz/corpus/TARGET; fuzz/corpus/ is never written) and writes what it
#     finds to build-fuzz/findings/TARGET/: the input, and beside it INPUT.log with libFuzzer's
#     report. After a finding the target starts again for the time that is left; an input with
#     the same kind and top frame as one already kept is dropped. Exit status 1 when a target
#     found something.
# or
#   bash scripts/fuzz.sh --regressions [TARGET...]
#     runs every file of fuzz/regressions/TARGET/ once through its target and says which still
#     fail. Exit status 1 when one does.
# Exit status 2 for a bad command line or a target that could not run.
set -uo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ATTEND_FUZZ_BUILD_DIR:-$root/build-fuzz}"
jobs="${ATTEND_FUZZ_JOBS:-2}"

usage() {
  sed -n '2,16p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
}

# The targets are the fuzz/*_fuzzer.cc files.
all_targets=()
for source in "$root"/fuzz/*_fuzzer.cc; do
  name="$(basename "$source" _fuzzer.cc)"
  all_targets+=("$name")
done

# Longest input each target is given: a little more than its largest seed, so that the fuzzer
# spends its time on the format and not on megabytes of filler.
max_len_of() {
  case "$1" in
    config) echo 16384 ;;
    scene | frames_jsonl | eval_run | compare_run | kitti_files) echo 8192 ;;
    pfm | objects_csv | tracks_csv | skin_text) echo 4096 ;;
    otb_boxes | skin_model) echo 2048 ;;
    *) echo 1024 ;;  # config_set, sequence_yaml
  esac
}

seconds=600
mode=fuzz
targets=()
while (($# > 0)); do
  case "$1" in
    --seconds)
      if (($# < 2)) || ! [[ "$2" =~ ^[0-9]+$ ]] || (($2 < 1)); then
        echo "fuzz.sh: --seconds needs a whole number of seconds >= 1" >&2
        exit 2
      fi
      seconds="$2"
      shift 2
      ;;
    --seconds=*)
      seconds="${1#--seconds=}"
      if ! [[ "$seconds" =~ ^[0-9]+$ ]] || ((seconds < 1)); then
        echo "fuzz.sh: --seconds needs a whole number of seconds >= 1" >&2
        exit 2
      fi
      shift
      ;;
    --regressions)
      mode=regressions
      shift
      ;;
    -h | --help)
      usage
      exit 0
      ;;
    -*)
      echo "fuzz.sh: unknown option $1 (see --help)" >&2
      exit 2
      ;;
    *)
      if [[ ! -f "$root/fuzz/$1_fuzzer.cc" ]]; then
        echo "fuzz.sh: no target '$1'; the targets are: ${all_targets[*]}" >&2
        exit 2
      fi
      targets+=("$1")
      shift
      ;;
  esac
done
if ((${#targets[@]} == 0)); then
  targets=("${all_targets[@]}")
fi

# UBSan reports are fatal in this build (cmake/AttendFuzzing.cmake); the stack makes them
# useful. LeakSanitizer runs after each input, as libFuzzer asks it to.
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"

# --- Build ------------------------------------------------------------------------------------
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  echo "fuzz.sh: configuring $build"
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DATTEND_BUILD_FUZZERS=ON \
    -DATTEND_BUILD_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null || exit 2
fi
build_targets=()
for target in "${targets[@]}"; do build_targets+=(--target "fuzz_$target"); done
echo "fuzz.sh: building ${targets[*]} in $build"
cmake --build "$build" -j"$jobs" "${build_targets[@]}" >"$build/fuzz-build.log" 2>&1 || {
  tail -n 40 "$build/fuzz-build.log" >&2
  echo "fuzz.sh: the build failed; the whole log is $build/fuzz-build.log" >&2
  exit 2
}

# --- Reading libFuzzer's reports ---------------------------------------------------------------

# The kind of a finding: the sanitizer's or libFuzzer's own words.
finding_kind() {
  local log="$1" line
  local pattern='runtime error:|ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|fuzz target:'
  line="$(grep -a -m1 -E "$pattern" "$log")"
  case "$line" in
    *"runtime error:"*) echo "UBSan:${line#*runtime error:}" ;;
    *"ERROR: AddressSanitizer: "*)
      line="${line#*AddressSanitizer: }"
      echo "ASan: ${line%% on *}"
      ;;
    *"ERROR: LeakSanitizer: "*) echo "LeakSanitizer: ${line#*LeakSanitizer: }" ;;
    *"ERROR: libFuzzer: "*)
      local kind="${line#*libFuzzer: }"
      kind="${kind%% (*}"
      local thrown
      thrown="$(grep -a -m1 -A1 "terminate called after throwing" "$log" | tr '\n' ' ')"
      if [[ -n "$thrown" ]]; then
        echo "uncaught exception: ${thrown#terminate called after throwing an instance of }"
      else
        echo "libFuzzer: $kind"
      fi
      ;;
    *"fuzz target:"*) echo "check failed:${line#*fuzz target:}" ;;
    *) echo "unknown (see the log)" ;;
  esac
}

# The first frames of the report in the project's own code, "function file:line", one a line:
# those outside the fuzz harness, or the harness's when the stack has no others (an exception
# thrown by a header-only library the harness called).
project_frames() {
  local log="$1" count="$2" frames
  frames="$(grep -a -E '^ *#[0-9]+ 0x[0-9a-f]+ in ' "$log" | grep -a -F " $root/" |
    sed -E 's/^ *#[0-9]+ 0x[0-9a-f]+ in (.*) ([^ ]+)$/\1 \2/' |
    sed -E "s| $root/| |; s/:[0-9]+\$//; s/\\(anonymous namespace\\):://g")"
  if grep -a -q -v ' fuzz/' <<<"$frames"; then frames="$(grep -a -v ' fuzz/' <<<"$frames")"; fi
  # Each frame as "function file:line", the function without its parameter list.
  awk -v n="$count" '
    NF {
      place = $NF
      name = substr($0, 1, length($0) - length(place) - 1)
      sub(/ const$/, "", name)
      if (substr(name, length(name)) == ")") {
        depth = 0
        for (i = length(name); i > 0; --i) {
          c = substr(name, i, 1)
          if (c == ")") ++depth
          if (c == "(" && --depth == 0) break
        }
        if (i > 1) name = substr(name, 1, i - 1)
      }
      line = name " " place
      if (!seen[line]++) { print line; if (++printed >= n) exit }
    }' <<<"$frames"
}

# What makes two findings the same for dropping repeats: the kind without the numbers and bytes
# that vary from input to input (an exception by its type alone, a failed check without the
# values it quotes), and the top project frame.
signature_of() {
  local kind="$1" top="$2"
  kind="${kind%%what():*}"
  [[ "$kind" == "check failed:"* ]] && kind="${kind%%\'*}"
  kind="$(sed -E 's/0x[0-9A-Fa-f]+/N/g; s/[-+]?[0-9]+([.][0-9]+)?(e[-+]?[0-9]+)?/N/g' <<<"$kind")"
  echo "$kind @ $top"
}

# --- Regressions -------------------------------------------------------------------------------
if [[ "$mode" == regressions ]]; then
  failed=0
  replayed=0
  # A crashing target leaves its scratch folder behind; they all go at the end.
  scratch="$build/tmp/regressions"
  mkdir -p "$scratch"
  for target in "${targets[@]}"; do
    folder="$root/fuzz/regressions/$target"
    [[ -d "$folder" ]] || continue
    for input in "$folder"/*; do
      [[ -f "$input" ]] || continue
      replayed=$((replayed + 1))
      log="$scratch/replay.log"
      if TMPDIR="$scratch" "$build/fuzz/fuzz_$target" -timeout=10 -rss_limit_mb=2048 "$input" \
        >"$log" 2>&1; then
        echo "ok     $target/${input##*/}"
      else
        failed=$((failed + 1))
        echo "FAILS  $target/${input##*/}: $(finding_kind "$log")"
        project_frames "$log" 3 | sed 's/^/         at /'
      fi
    done
  done
  rm -rf "$scratch"
  echo "fuzz.sh: $replayed regression inputs replayed, $failed still fail"
  ((failed == 0)) || exit 1
  exit 0
fi

# --- Fuzzing -----------------------------------------------------------------------------------
summary="$build/findings/summary.txt"
mkdir -p "$build/findings"
: >"$summary"
found_any=0
for target in "${targets[@]}"; do
  binary="$build/fuzz/fuzz_$target"
  corpus="$build/corpus/$target"
  findings="$build/findings/$target"
  scratch="$build/tmp/$target"
  # The previous run's findings are kept one generation, beside the new ones.
  if [[ -d "$findings" ]] && [[ -n "$(ls -A "$findings")" ]]; then
    rm -rf "$findings.previous"
    mv "$findings" "$findings.previous"
  fi
  mkdir -p "$corpus" "$findings" "$scratch"
  cp -n "$root/fuzz/corpus/$target"/* "$corpus"/ 2>/dev/null
  dict=()
  [[ -f "$root/fuzz/dict/$target.dict" ]] && dict=(-dict="$root/fuzz/dict/$target.dict")

  echo "fuzz.sh: $target for ${seconds} s (max_len $(max_len_of "$target"))"
  start=$(date +%s)
  deadline=$((start + seconds))
  signatures=()
  kept=0
  dropped=0
  restarts=0
  executions=0
  while :; do
    now=$(date +%s)
    left=$((deadline - now))
    ((left > 0)) || break
    log="$findings/run.log"
    before="$(ls "$findings" | grep -E '^(crash|leak|timeout|oom|slow-unit)-' | sort)"
    TMPDIR="$scratch" "$binary" "$corpus" -max_total_time="$left" \
      -max_len="$(max_len_of "$target")" -timeout=10 -rss_limit_mb=2048 \
      -artifact_prefix="$findings/" -print_final_stats=1 "${dict[@]}" >"$log" 2>&1
    status=$?
    runs="$(grep -a -m1 -o 'stat::number_of_executed_units: [0-9]*' "$log" | grep -o '[0-9]*$')"
    executions=$((executions + ${runs:-0}))
    after="$(ls "$findings" | grep -E '^(crash|leak|timeout|oom|slow-unit)-' | sort)"
    new="$(comm -13 <(echo "$before") <(echo "$after"))"
    if [[ -z "$new" ]]; then
      if ((status != 0)); then
        echo "fuzz.sh: $target stopped with status $status and no finding; see $log" >&2
        echo "$target: stopped with status $status and no finding ($log)" >>"$summary"
        found_any=2
      else
        rm -f "$log"
      fi
      break
    fi
    kind="$(finding_kind "$log")"
    top="$(project_frames "$log" 1)"
    signature="$(signature_of "$kind" "$top")"
    artifact="$findings/$(echo "$new" | head -n 1)"
    duplicate=0
    for seen in "${signatures[@]}"; do [[ "$seen" == "$signature" ]] && duplicate=1; done
    if ((duplicate)); then
      rm -f "$artifact" "$log"
      dropped=$((dropped + 1))
    else
      signatures+=("$signature")
      mv "$log" "$artifact.log"
      kept=$((kept + 1))
      {
        echo "$target: $kind"
        echo "  input: $artifact ($(stat -c %s "$artifact") bytes)"
        project_frames "$artifact.log" 4 | sed 's/^/  at /'
      } | tee -a "$summary"
    fi
    restarts=$((restarts + 1))
    # A target that finds only what it has found already is not exploring any more.
    if ((restarts >= 25)); then
      echo "fuzz.sh: $target stopped after 25 findings in this run" | tee -a "$summary"
      break
    fi
  done
  rm -rf "$scratch"
  took=$(($(date +%s) - start))
  echo "fuzz.sh: $target ran ${took} s, $executions inputs: $kept distinct findings" \
    "($dropped more of the same) in $findings" | tee -a "$summary"
  ((kept > 0)) && ((found_any == 0)) && found_any=1
done
echo "fuzz.sh: summary in $summary"
exit "$found_any"
