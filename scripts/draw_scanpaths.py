#!/usr/bin/env python3
"""Draws attend's order of attention beside observers' scanpaths over their images.

    python3 scripts/draw_scanpaths.py --dataset DATASET --maps MAPS --ids 101 150 --out F.png
        [--observers 2] [--length 8] [--keep-first]

MAPS is a folder of `attend saliency --scanpath K` (its scanpath.json); DATASET is in the layout
of docs/FIXATIONS.md (stimuli/<id>.<ext>, fixations/<id>.txt, each subject's lines in viewing
order). One row per image: attend's steps, then the first observers' fixations (subjects in
file order), each numbered in order and joined by its saccades, over the image. Needs only
Debian's python3-numpy and python3-matplotlib.
"""
import argparse
import json
import pathlib
import sys

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.image import imread
except ImportError as error:  # pragma: no cover
    sys.exit(f"draw_scanpaths.py: {error}; run it with Debian's /usr/bin/python3")


def fail(message, status=3):
    print(f"draw_scanpaths.py: {message}", file=sys.stderr)
    sys.exit(status)


def stimulus(dataset, image_id):
    for ext in (".jpg", ".jpeg", ".png", ".ppm", ".pgm", ".bmp"):
        path = dataset / "stimuli" / (image_id + ext)
        if path.is_file():
            return path
    fail(f"{dataset / 'stimuli'}: no image {image_id}")


def observers(dataset, image_id):
    """Each subject's (x, y) fixations in file order, subjects in order of first appearance."""
    path = dataset / "fixations" / (image_id + ".txt")
    if not path.is_file():
        fail(f"{path}: no such fixation file")
    paths = {}
    for number, line in enumerate(path.read_text().splitlines(), 1):
        fields = line.split()
        if not fields or fields[0].startswith("#"):
            continue
        try:
            subject, x, y = int(fields[0]), float(fields[1]), float(fields[2])
        except (ValueError, IndexError):
            fail(f"{path}:{number}: not 'subject x y ...'")
        paths.setdefault(subject, []).append((x - 1.0, y - 1.0))  # 1-based to 0-based
    return list(paths.values())


def draw(axis, image, points, colour, title):
    axis.imshow(image)
    if points:
        xs, ys = zip(*points)
        axis.plot(xs, ys, "-", color=colour, linewidth=1.5, alpha=0.8)
        for k, (x, y) in enumerate(points, 1):
            axis.add_patch(plt.Circle((x, y), radius=max(image.shape[:2]) * 0.018, color=colour,
                                      alpha=0.85))
            axis.text(x, y, str(k), color="white", fontsize=8, ha="center", va="center")
    axis.set_title(title, fontsize=9)
    axis.axis("off")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dataset", required=True)
    parser.add_argument("--maps", required=True)
    parser.add_argument("--ids", nargs="+", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--observers", type=int, default=2)
    parser.add_argument("--length", type=int, default=8)
    parser.add_argument("--keep-first", action="store_true",
                        help="keep each observer's first fixation (dropped by default, as "
                             "attend eval-scanpaths does)")
    args = parser.parse_args()
    if args.observers < 0 or args.length < 1:
        fail("--observers must be >= 0 and --length >= 1", 2)
    dataset, maps = pathlib.Path(args.dataset), pathlib.Path(args.maps)
    try:
        scanpaths = json.loads((maps / "scanpath.json").read_text())
    except (OSError, ValueError) as error:
        fail(f"{maps / 'scanpath.json'}: {error}")
    columns = 1 + args.observers
    figure, axes = plt.subplots(len(args.ids), columns, figsize=(4 * columns, 3.2 * len(args.ids)),
                                squeeze=False)
    for row, image_id in enumerate(args.ids):
        if image_id not in scanpaths:
            fail(f"{maps / 'scanpath.json'}: no scanpath for image {image_id}")
        image = imread(stimulus(dataset, image_id))
        model = [(step["x"], step["y"]) for step in scanpaths[image_id]][: args.length]
        draw(axes[row][0], image, model, "tab:red", f"{image_id}: attend")
        people = observers(dataset, image_id)
        for k in range(args.observers):
            axis = axes[row][1 + k]
            if k >= len(people):
                axis.axis("off")
                continue
            path = people[k] if args.keep_first else people[k][1:]
            draw(axis, image, path[: args.length], "tab:blue", f"{image_id}: observer {k + 1}")
    figure.tight_layout()
    figure.savefig(args.out, dpi=80)
    print(args.out)


if __name__ == "__main__":
    main()
