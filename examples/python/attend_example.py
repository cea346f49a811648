#!/usr/bin/env python3
"""attend from Python: run a sequence with a Python feature beside the built-in ones, score it
against its ground truth, and plot the saliency and the targets of a few frames.

    PYTHONPATH=build/python python3 examples/python/attend_example.py \
        [SEQUENCE] [--frames 0:39] [--config FILE] [--out attend_example.png]

SEQUENCE is a stereo sequence folder (left/, right/, gt/) or a monocular one; without it the
bundled lab sequence is used. --config runs that configuration with the Python feature added
to its features. Needs numpy and matplotlib (python3-matplotlib).
"""

import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no window
import matplotlib.patches as patches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

import attend  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import motion_energy  # noqa: E402,F401  (registers the feature "motion_energy")

COLOURS = {"new": "yellow", "tracked": "lime", "resumed": "cyan", "occluded": "orange",
           "lost": "red", "released": "grey"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sequence", nargs="?", help="sequence folder (default: bundled lab)")
    parser.add_argument("--frames", default="0:39", help="FIRST:LAST, inclusive")
    parser.add_argument("--show", type=int, default=4, help="frames to plot")
    parser.add_argument("--out", default="attend_example.png", help="the figure (PNG)")
    parser.add_argument("--config", help="a configuration file instead of the built-in one")
    args = parser.parse_args()

    sequence = args.sequence or attend.bundled_sequence()
    first, last = (int(v) for v in args.frames.split(":"))
    stereo = os.path.isdir(os.path.join(sequence, "right"))
    features = [{"name": "colour_contrast"}, {"name": "intensity_contrast"},
                {"name": "motion_energy", "weight": 2.0, "blur": 9}]
    if stereo:
        features.append({"name": "disparity"})

    config = {"features": features}
    settings = []
    if args.config:
        # The file's own features (one flow map a line in the effective configuration), and
        # the Python one after them.
        config = args.config
        lines = attend.configuration(config).split("\nfeatures:\n")[1].splitlines()
        entries = [line[4:] for line in lines[:next(
            i for i, line in enumerate(lines) if not line.startswith("  - "))]]
        entries.append("{name: motion_energy, weight: 2.0, blur: 9}")
        settings = ["features=[" + ", ".join(entries) + "]"]

    # 1. Frame by frame, the maps in hand.
    pipeline = attend.Pipeline(config=config, set=settings)
    shown = {}
    every = max(1, (last - first + 1) // args.show)
    for index, (left, right) in enumerate(attend.frames(sequence)):
        if index < first:
            continue
        if index > last:
            break
        result = pipeline.process(left, right, index=index)
        if (index - first) % every == 0 and len(shown) < args.show:
            # The maps share the pipeline's buffers; a map held here keeps its values.
            shown[index] = (left, result)
        print(f"frame {index}: {len(result.targets)} targets, "
              f"{sum(result.timings.values()):.1f} ms")

    # 2. The same configuration as a run folder, scored against the ground truth.
    run = attend.run(sequence, config=config,
                     set=settings + ["plugins=[" + motion_energy.__file__ + "]"],
                     frames=args.frames, out=os.path.splitext(args.out)[0] + "-run",
                     overwrite=True)
    print(f"run folder {run.dir}: {run.summary['frames']} frames, "
          f"{run.summary['fps']:.1f} frames/s")
    if os.path.isdir(os.path.join(sequence, "gt")):
        scores = attend.eval_run(run.dir)
        print("scores:", {k: round(scores[k], 3) for k in ("coverage", "revisits", "mean_iou")})
        mot = scores["mot"]["iou_0.5"]  # MOTChallenge's match at IoU 0.5
        print("MOT at IoU 0.5:", {k: round(mot[k], 3) for k in ("IDF1", "MOTA", "purity")})
    targets = run.targets_frame()
    print(targets.groupby("id").frame.agg(["min", "max", "count"]).head(10))

    # 3. The figure: each chosen frame with its targets, its saliency and its motion energy.
    figure, axes = plt.subplots(3, len(shown), figsize=(3.2 * len(shown), 7.2), squeeze=False)
    for column, (index, (left, result)) in enumerate(sorted(shown.items())):
        scale_x = left.shape[1] / result.working_size[0]
        scale_y = left.shape[0] / result.working_size[1]
        axes[0][column].imshow(left[:, :, ::-1])
        axes[0][column].set_title(f"frame {index}")
        for target in result.targets:
            x, y, w, h = target["bbox"]
            axes[0][column].add_patch(patches.Rectangle(
                (x, y), w, h, fill=False, linewidth=1.5,
                edgecolor=COLOURS.get(target["state"], "white")))
            axes[0][column].text(x, y - 2, str(target["id"]), color="white", fontsize=7)
        extent = (0, result.working_size[0] * scale_x, result.working_size[1] * scale_y, 0)
        axes[1][column].imshow(result.saliency, cmap="inferno", extent=extent)
        axes[2][column].imshow(result.features["motion_energy"], cmap="viridis", extent=extent)
    axes[1][0].set_ylabel("saliency")
    axes[2][0].set_ylabel("motion_energy (Python)")
    for axis in axes.flat:
        axis.set_xticks([])
        axis.set_yticks([])
    figure.tight_layout()
    figure.savefig(args.out, dpi=100)
    print(f"figure: {args.out}")


if __name__ == "__main__":
    main()
