#!/usr/bin/env bash
# Soak benchmark (not a test): N frames (default 10000) through `attend run` with the default
# configuration, sampling the process's resident memory, threads and open files every few
# seconds. The sequence is the bundled lab scene's 120 stereo frames repeated by symbolic links
# (frame i is frame i mod 120), so it needs no disk beyond the run's own dumps.
#
#   bash bench/soak.sh [--frames N] [--every SECONDS] [--attend BIN] [--out DIR] [-- RUN-ARGS...]
#
# Prints one line per sample (seconds, frames done, RSS MB, threads, open files) to
# DIR/samples.csv and a summary at the end: RSS in the first and the last minute, its maximum,
# and the ranges of threads and open files.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames=10000
every=5
bin="$root/build/attend"
out="$(mktemp -d /tmp/attend-soak.XXXXXX)"
run_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --frames) frames="$2"; shift 2 ;;
    --every) every="$2"; shift 2 ;;
    --attend) bin="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --) shift; run_args=("$@"); break ;;
    *) echo "soak.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ -x "$bin" ] || { echo "soak.sh: no attend binary at $bin (build first: bash scripts/build.sh)" >&2; exit 2; }
mkdir -p "$out"

# The bundled sequence, rendered once, then linked N times over.
lab="$out/lab"
if [ ! -d "$lab/left" ]; then
  "$bin" synth "$root/sequences/lab.yaml" --out "$lab" > /dev/null
fi
seq="$out/sequence"
rm -rf "$seq"
mkdir -p "$seq/left" "$seq/right"
count=$(ls "$lab/left" | wc -l)
for view in left right; do
  (
    cd "$seq/$view"
    i=0
    while [ $i -lt "$frames" ]; do
      printf -v name '%06d.png' "$i"
      printf -v source '%06d.png' $((i % count))
      ln -s "$lab/$view/$source" "$name"
      i=$((i + 1))
    done
  )
done

"$bin" run --sequence "$seq" --out "$out/run" --overwrite --quiet "${run_args[@]}" \
  > "$out/run.log" 2>&1 &
pid=$!
start=$(date +%s)
echo "seconds,frames,rss_mb,threads,open_files" > "$out/samples.csv"
while kill -0 "$pid" 2> /dev/null; do
  status="/proc/$pid/status"
  rss=$(awk '/^VmRSS:/ {printf "%.1f", $2 / 1024}' "$status" 2> /dev/null || echo "")
  threads=$(awk '/^Threads:/ {print $2}' "$status" 2> /dev/null || echo "")
  files=$(ls "/proc/$pid/fd" 2> /dev/null | wc -l)
  done_frames=0
  [ -f "$out/run/frames.jsonl" ] && done_frames=$(wc -l < "$out/run/frames.jsonl")
  [ -n "$rss" ] && echo "$(( $(date +%s) - start )),$done_frames,$rss,$threads,$files" >> "$out/samples.csv"
  sleep "$every"
done
wait "$pid" || { echo "soak.sh: attend run failed:" >&2; tail -3 "$out/run.log" >&2; exit 1; }

python3 - "$out/samples.csv" "$out/run/summary.json" <<'PY'
import csv, json, sys
rows = [r for r in csv.DictReader(open(sys.argv[1]))]
if not rows:
    sys.exit("soak.sh: no samples (the run ended within the first interval)")
t = [int(r["seconds"]) for r in rows]
rss = [float(r["rss_mb"]) for r in rows]
end = t[-1]
first = [m for s, m in zip(t, rss) if 60 <= s < 120] or rss[: max(1, len(rss) // 10)]
last = [m for s, m in zip(t, rss) if s >= end - 60]
threads = [int(r["threads"]) for r in rows]
files = [int(r["open_files"]) for r in rows]
summary = json.load(open(sys.argv[2]))
print(f"{summary['frames']} frames in {summary['wall_seconds']:.0f} s ({summary['fps']:.1f} frames/s)")
print(f"samples {len(rows)} over {end} s")
print(f"RSS MB: second minute mean {sum(first)/len(first):.1f}, last minute mean {sum(last)/len(last):.1f}, max {max(rss):.1f}, min {min(rss):.1f}")
print(f"threads {min(threads)}..{max(threads)}, open files {min(files)}..{max(files)}")
PY
echo "samples: $out/samples.csv"
