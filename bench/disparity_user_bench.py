#!/usr/bin/env python3
"""attend.disparity against OpenCV's StereoSGBM as a user calls them (docs/DISPARITY.md, "As a
user calls it"; issue 47): one process, warm, one thread, colour frames in, the calls
alternated (the side that goes first alternates too), on every Middlebury pair found in the
data folder. The peer is the issue's:

    cv2.StereoSGBM_create(0, D rounded up to 16, 5, 600, 2400, 1, 63, 10, 100, 2, MODE_SGBM)

Times are each call's wall clock, the median of --calls calls; bad1 is the share of pixels with
known ground truth (> 0) that are more than 1 px off, a pixel without a disparity (attend's NaN,
SGBM's negative values) counted as wrong on both sides.

    PYTHONPATH=build/python /usr/bin/python3 bench/disparity_user_bench.py [--data ../shared/data]

It needs OpenCV's Python module (Debian's python3-opencv) for the peer.
"""

import argparse
import os
import statistics
import time

import numpy as np

try:
    import cv2
except ImportError:  # pragma: no cover - a message, not a test
    raise SystemExit("disparity_user_bench: needs OpenCV's Python module for the peer "
                     "(apt install python3-opencv)")

import attend

# (folder, pair, left, right, ground truth, its scale, D): as bench/disparity_bench.cc.
PAIRS = [("middlebury", "tsukuba", "im3.png", "im4.png", "disp3.pgm", 16.0, 16),
         ("middlebury", "venus", "im2.png", "im6.png", "disp2.pgm", 8.0, 20),
         ("middlebury", "teddy", "im2.png", "im6.png", "disp2.png", 4.0, 60),
         ("middlebury", "cones", "im2.png", "im6.png", "disp2.png", 4.0, 60)] + [
    ("middlebury2005", name, "left.png", "right.png", "disp_left.png", 3.0, 80)
    for name in ("Art", "Books", "Dolls", "Laundry", "Moebius", "Reindeer")]


def bad1(disparity, truth):
    known = truth > 0
    wrong = ~np.isfinite(disparity) | (disparity < 0) | (np.abs(disparity - truth) > 1.0)
    return 100.0 * np.count_nonzero(wrong & known) / np.count_nonzero(known)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=os.path.join(os.path.dirname(__file__), "..", "..",
                                                       "shared", "data"))
    parser.add_argument("--calls", type=int, default=5)
    args = parser.parse_args()
    cv2.setNumThreads(1)
    rows = []
    for folder, name, left_name, right_name, truth_name, scale, d in PAIRS:
        base = os.path.join(args.data, folder, name)
        if not os.path.isdir(base):
            print(f"{folder}/{name}: not found, skipped")
            continue
        left = cv2.imread(os.path.join(base, left_name), cv2.IMREAD_COLOR)
        right = cv2.imread(os.path.join(base, right_name), cv2.IMREAD_COLOR)
        truth = cv2.imread(os.path.join(base, truth_name), cv2.IMREAD_UNCHANGED)
        truth = truth.astype(np.float32) / scale
        sgbm = cv2.StereoSGBM_create(0, (d + 15) // 16 * 16, 5, 600, 2400, 1, 63, 10, 100, 2,
                                     cv2.STEREO_SGBM_MODE_SGBM)
        ours = attend.disparity(left, right, max_disparity=d)  # warm-up
        theirs = sgbm.compute(left, right).astype(np.float32) / 16.0
        times = {"attend": [], "sgbm": []}
        calls = {"attend": lambda: attend.disparity(left, right, max_disparity=d),
                 "sgbm": lambda: sgbm.compute(left, right)}
        for k in range(args.calls):
            for side in (("attend", "sgbm") if k % 2 == 0 else ("sgbm", "attend")):
                start = time.perf_counter()
                calls[side]()
                times[side].append(time.perf_counter() - start)
        ms = {side: 1e3 * statistics.median(t) for side, t in times.items()}
        rows.append((name, left.shape[1], left.shape[0], d, ms["attend"], ms["sgbm"],
                     bad1(ours, truth), bad1(theirs, truth)))
    print("| pair | size | D | attend ms | SGBM ms | speed (SGBM ms / attend ms) | attend bad1 % "
          "| SGBM bad1 % |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for name, w, h, d, ours_ms, sgbm_ms, ours_bad, sgbm_bad in rows:
        print(f"| {name} | {w}x{h} | {d} | {ours_ms:.1f} | {sgbm_ms:.1f} | {sgbm_ms / ours_ms:.2f} "
              f"| {ours_bad:.2f} | {sgbm_bad:.2f} |")
    faster = sum(r[5] >= r[4] for r in rows)
    better = sum(r[6] < r[7] for r in rows)
    print(f"\nattend at least as fast on {faster} of {len(rows)} pairs; bad1 below SGBM's on "
          f"{better} of {len(rows)}")


if __name__ == "__main__":
    main()
