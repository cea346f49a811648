#!/usr/bin/env python3
"""The Python module's costs (docs/PERFORMANCE.md, "The Python module"):

1. attend.Pipeline.process over the bundled lab frames against the same loop of `attend run`
   in C++ (the module's _reference_loop: each frame through the pipeline, its record in input
   pixels and its JSON line, as pipeline/run.cc's RunFrame, less the reading and the run
   folder), frames held in memory in both, one thread, in one process, alternated pass by
   pass (the side that goes first alternates too); each pass a new pipeline;
2. a Python feature plugin's overhead a frame beyond its own compute: the time attend
   measures for the feature less the time spent inside its compute(), for a feature that
   returns a map it already holds.

Times are the thread's CPU time (the loop runs on the calling thread with threads=1), which
another process on the other core disturbs less than the wall clock; both are printed.

    PYTHONPATH=build/python python3 bench/python_bench.py [--passes 20]
"""

import argparse
import statistics
import time

import numpy as np

import attend
from attend import _attend

SETTINGS = ["threads=1", "output.dump=[]"]


def python_pass(frames):
    """(CPU ms, wall ms) a frame of one pass of Pipeline.process, as a user's loop keeps it."""
    pipeline = attend.Pipeline(set=SETTINGS)
    cpu, wall = time.thread_time(), time.perf_counter()
    for left, right in frames:
        result = pipeline.process(left, right)
    cpu, wall = time.thread_time() - cpu, time.perf_counter() - wall
    del result
    return 1000.0 * cpu / len(frames), 1000.0 * wall / len(frames)


def cpp_pass(frames):
    options = attend._configuration(None, SETTINGS)
    cpu, wall, _ = _attend._reference_loop(options, frames)
    return cpu, wall


class HeldMap:
    """A feature whose own compute is next to nothing: it returns a map it holds."""

    own_ms = []

    def __init__(self):
        self.map = None

    def compute(self, context):
        start = time.perf_counter()
        if self.map is None:
            height, width = context.left.shape[:2]
            self.map = np.ones((height, width), np.float32)
        HeldMap.own_ms.append((time.perf_counter() - start) * 1000.0)
        return self.map


def plugin_overhead(frames, rounds):
    """Per round, the mean over frames of (attend's time for the feature - its compute's own
    time), ms."""
    attend.register_feature("held_map", HeldMap)
    settings = ["threads=1", "features=[{name: colour_contrast}, {name: held_map}]"]
    overheads = []
    for _ in range(rounds):
        pipeline = attend.Pipeline(set=settings)
        HeldMap.own_ms.clear()
        measured = [pipeline.process(left, right).feature_ms["held_map"]
                    for left, right in frames]
        overheads.append(statistics.mean(m - o for m, o in zip(measured, HeldMap.own_ms)))
    return overheads


def describe(name, values):
    cpu = [v[0] for v in values]
    wall = [v[1] for v in values]
    print(f"{name}: CPU median {statistics.median(cpu):.3f} ms a frame (min {min(cpu):.3f}), "
          f"wall median {statistics.median(wall):.3f} (min {min(wall):.3f})")
    return statistics.median(cpu), min(cpu), statistics.median(wall)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--passes", type=int, default=20, help="timed passes a side")
    args = parser.parse_args()

    sequence = attend.bundled_sequence()
    frames = list(attend.frames(sequence))
    cpp_pass(frames)  # warm-up of both sides
    python_pass(frames)
    cpp, python, ratios = [], [], []
    for index in range(args.passes):
        order = [("cpp", cpp_pass), ("python", python_pass)]
        if index % 2:
            order.reverse()
        got = {name: run(frames) for name, run in order}
        cpp.append(got["cpp"])
        python.append(got["python"])
        ratios.append(got["python"][0] / got["cpp"][0])
    print(f"frames: {len(frames)} of {sequence}, {frames[0][0].shape[1]}x"
          f"{frames[0][0].shape[0]}, one thread, {args.passes} alternated passes a side")
    c_median, c_min, c_wall = describe("attend run loop (C++)    ", cpp)
    p_median, p_min, p_wall = describe("attend.Pipeline.process  ", python)
    print(f"Python over C++, CPU: {100.0 * (p_median / c_median - 1.0):+.2f} % (medians), "
          f"{100.0 * (p_min / c_min - 1.0):+.2f} % (minima), "
          f"{100.0 * (statistics.median(ratios) - 1.0):+.2f} % (median of the pairs' ratios); "
          f"wall: {100.0 * (p_wall / c_wall - 1.0):+.2f} % (medians)")
    overheads = plugin_overhead(frames, 5)
    print(f"Python feature overhead beyond its compute: median "
          f"{1000.0 * statistics.median(overheads):.1f} us a frame "
          f"(rounds: {', '.join(f'{1000.0 * o:.1f}' for o in overheads)})")


if __name__ == "__main__":
    main()
