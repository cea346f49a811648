#!/usr/bin/env python3
"""Cross-validation of tracker settings over OTB-layout sequences (docs/TRACKING.md,
"Cross-validation").

Every variant of a grid file (a JSON list of {"name": ..., "set": ["key=value", ...]}) runs
`attend track` from the first ground-truth box over every sequence and is scored with
`attend eval-tracking` (success AUC). The sequences are split into folds; for each fold the
variant with the best mean AUC on the other folds' sequences (training) is chosen, and its
mean AUC on the fold's own sequences (held out) is reported. The table also gives every
variant's held-out mean per fold, so that each choice's effect is measured on data that did not
choose it. The variant to ship is the one chosen by the most folds (ties: the best mean of the
training means); its held-out means are the numbers to report.

  scripts/tracking_crossval.py --otb ../shared/data/otb --grid scripts/tracking_grid.json \\
      --out /tmp/crossval [--attend build/attend] [--jobs 2] [--markdown FILE]

Results are cached per variant in OUT/<variant>/scores.json: a rerun with a grown grid only
runs the new variants.
"""
import argparse
import concurrent.futures
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

# The OTB sequences and the ground truth file scored (Jogging: its first jogger), and the
# folds: five pairs, fixed before any run, each pairing a sequence the bounded mode did well on
# with one it did badly on (the table), so that every fold holds out a hard case.
SEQUENCES = {
    "Bolt2": "groundtruth_rect.txt",
    "Couple": "groundtruth_rect.txt",
    "Crossing": "groundtruth_rect.txt",
    "Deer": "groundtruth_rect.txt",
    "Dog1": "groundtruth_rect.txt",
    "Freeman1": "groundtruth_rect.txt",
    "Girl": "groundtruth_rect.txt",
    "Jogging": "groundtruth_rect.1.txt",
    "MotorRolling": "groundtruth_rect.txt",
    "Skiing": "groundtruth_rect.txt",
}
FOLDS = [
    ["Couple", "Bolt2"],
    ["Crossing", "Freeman1"],
    ["Deer", "MotorRolling"],
    ["Dog1", "Skiing"],
    ["Jogging", "Girl"],
]


def first_box(path):
    fields = open(path).readline().replace(",", " ").replace("\t", " ").split()
    x, y, w, h = (float(v) for v in fields[:4])
    # OTB boxes are 1-based; attend's are 0-based.
    return f"{round(x - 1)},{round(y - 1)},{round(w)},{round(h)}"


def run_one(attend, otb, out, name, sets):
    truth = otb / name / SEQUENCES[name]
    folder = out / name
    command = [attend, "track", "--images", str(otb / name / "img"), "--init", first_box(truth),
               "--out", str(folder), "--overwrite"]
    for item in sets:
        command += ["--set", item]
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        raise RuntimeError(f"{name}: attend track exited {run.returncode}: {run.stderr.strip()}")
    scored = subprocess.run([attend, "eval-tracking", str(folder / "tracks.csv"), "--gt", str(truth)],
                            capture_output=True, text=True, check=True)
    report = json.loads(scored.stdout)
    summary = json.loads((folder / "track.json").read_text())
    target = report["targets"][0]
    return name, {"auc": target["success_auc"], "precision": target["precision_20"],
                  "ms_per_frame": summary["ms_per_frame"]}


def run_variant(attend, otb, out, variant, jobs):
    folder = out / variant["name"]
    cache = folder / "scores.json"
    if cache.exists():
        cached = json.loads(cache.read_text())
        if cached.get("set") == variant["set"]:
            return cached["scores"]
    folder.mkdir(parents=True, exist_ok=True)
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        scores = dict(pool.map(lambda n: run_one(attend, otb, folder, n, variant["set"]), SEQUENCES))
    cache.write_text(json.dumps({"set": variant["set"], "scores": scores}, indent=1))
    return scores


def mean(values):
    return sum(values) / len(values)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--otb", required=True, type=Path)
    parser.add_argument("--grid", required=True, type=Path)
    parser.add_argument("--out", required=True, type=Path)
    parser.add_argument("--attend", default="build/attend")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--markdown", type=Path)
    args = parser.parse_args()
    for name, truth in SEQUENCES.items():
        if not (args.otb / name / truth).is_file():
            sys.exit(f"tracking_crossval: {args.otb / name / truth}: missing")
    grid = json.loads(args.grid.read_text())
    names = [v["name"] for v in grid]
    if len(set(names)) != len(names):
        sys.exit(f"tracking_crossval: {args.grid}: variant names repeat")
    scores = {}
    for variant in grid:
        scores[variant["name"]] = run_variant(args.attend, args.otb, args.out, variant, args.jobs)
        s = scores[variant["name"]]
        print(f"{variant['name']:28s} mean AUC {mean([s[n]['auc'] for n in SEQUENCES]):.3f}  "
              f"median ms {statistics.median([s[n]['ms_per_frame'] for n in SEQUENCES]):.2f}",
              flush=True)

    lines = []
    held = {}  # variant -> per fold held-out mean
    chosen = []
    for k, fold in enumerate(FOLDS):
        train = [n for n in SEQUENCES if n not in fold]
        train_means = {v: mean([scores[v][n]["auc"] for n in train]) for v in names}
        best = max(names, key=lambda v: train_means[v])
        chosen.append((best, train_means[best]))
        for v in names:
            held.setdefault(v, []).append(mean([scores[v][n]["auc"] for n in fold]))
    votes = {}
    for best, train_mean in chosen:
        count, total = votes.get(best, (0, 0.0))
        votes[best] = (count + 1, total + train_mean)
    ship = max(votes, key=lambda v: (votes[v][0], votes[v][1]))

    header = "| variant | settings | " + " | ".join(
        f"fold {k + 1} ({', '.join(f)})" for k, f in enumerate(FOLDS)) + " | mean of folds | spread (sd) | median ms/frame |"
    lines.append(header)
    lines.append("|" + "---|" * (len(FOLDS) + 5))
    for v in names:
        per = held[v]
        ms = statistics.median([scores[v][n]["ms_per_frame"] for n in SEQUENCES])
        settings = " ".join(next(x["set"] for x in grid if x["name"] == v)) or "(defaults)"
        mark = "**" if v == ship else ""
        lines.append(f"| {mark}{v}{mark} | `{settings}` | " + " | ".join(f"{x:.3f}" for x in per) +
                     f" | {mean(per):.3f} | {statistics.pstdev(per):.3f} | {ms:.2f} |")
    lines.append("")
    lines.append("| fold | held out | chosen on the other eight | its training mean | its held-out mean |")
    lines.append("|---|---|---|---:|---:|")
    nested = []
    for k, (fold, (best, train_mean)) in enumerate(zip(FOLDS, chosen)):
        nested.append(held[best][k])
        lines.append(f"| {k + 1} | {', '.join(fold)} | {best} | {train_mean:.3f} | {held[best][k]:.3f} |")
    lines.append("")
    lines.append(f"Nested estimate (each fold scored with the variant its training chose): mean "
                 f"{mean(nested):.3f}, sd {statistics.pstdev(nested):.3f} over the folds. Shipped: "
                 f"**{ship}** (chosen by {votes[ship][0]} of {len(FOLDS)} folds); its held-out "
                 f"fold means {', '.join(f'{x:.3f}' for x in held[ship])}, mean {mean(held[ship]):.3f}, "
                 f"sd {statistics.pstdev(held[ship]):.3f}.")
    lines.append("")
    lines.append("| sequence | " + " | ".join(names) + " |")
    lines.append("|---|" + "---:|" * len(names))
    for n in SEQUENCES:
        lines.append(f"| {n} | " + " | ".join(f"{scores[v][n]['auc']:.3f}" for v in names) + " |")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.markdown:
        args.markdown.write_text(text)


if __name__ == "__main__":
    main()
