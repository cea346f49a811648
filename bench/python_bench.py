#!/usr/bin/env python3
"""The Python module's costs (docs/PERFORMANCE.md, "The Python module"):

1. attend.Pipeline.process over the bundled lab frames against the same loop of `attend run`
   (bench/loop_bench), frames held in memory in both, one thread, alternated round by round;
2. a Python feature plugin's overhead a frame beyond its own compute: the time attend
   measures for the feature less the time spent inside its compute(), for a feature that
   returns a map it already holds.

    cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DATTEND_BUILD_BENCHMARKS=ON
    cmake --build build-bench --target loop_bench _attend
    PYTHONPATH=build-bench/python python3 bench/python_bench.py \
        --loop-bench build-bench/bench/loop_bench [--rounds 5] [--passes 3]
"""

import argparse
import json
import statistics
import subprocess
import time

import numpy as np

import attend


def python_passes(frames, settings, passes):
    """ms a frame of each timed pass, after one warm-up pass, a new pipeline a pass."""
    results = []
    for index in range(passes + 1):
        pipeline = attend.Pipeline(set=settings)
        start = time.perf_counter()
        for left, right in frames:
            result = pipeline.process(left, right)
        elapsed = (time.perf_counter() - start) * 1000.0 / len(frames)
        del result
        if index > 0:
            results.append(elapsed)
    return results


def cpp_passes(binary, settings, passes):
    command = [binary, "--passes", str(passes)]
    for setting in settings:
        command += ["--set", setting]
    output = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    return json.loads(output)["ms_per_frame"]


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
    """Mean over frames of (attend's time for the feature - its compute's own time), ms."""
    attend.register_feature("held_map", HeldMap)
    settings = ["threads=1", "features=[{name: colour_contrast}, {name: held_map}]"]
    overheads = []
    for _ in range(rounds):
        pipeline = attend.Pipeline(set=settings)
        HeldMap.own_ms.clear()
        measured = []
        for left, right in frames:
            measured.append(pipeline.process(left, right).feature_ms["held_map"])
        overheads.append(statistics.mean(m - o for m, o in zip(measured, HeldMap.own_ms)))
    return overheads


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--loop-bench", required=True, help="the loop_bench program")
    parser.add_argument("--rounds", type=int, default=5, help="alternated rounds")
    parser.add_argument("--passes", type=int, default=3, help="timed passes a round and side")
    args = parser.parse_args()

    sequence = attend.bundled_sequence()
    frames = list(attend.frames(sequence))
    settings = ["threads=1", "output.dump=[]"]
    cpp, python = [], []
    for round_index in range(args.rounds):
        # Alternated, and the side that goes first alternates too.
        sides = [("cpp", lambda: cpp_passes(args.loop_bench, settings, args.passes)),
                 ("python", lambda: python_passes(frames, settings, args.passes))]
        if round_index % 2:
            sides.reverse()
        for name, run in sides:
            (cpp if name == "cpp" else python).extend(run())
    cpp_median, python_median = statistics.median(cpp), statistics.median(python)
    print(f"frames: {len(frames)} of {sequence}, {frames[0][0].shape[1]}x"
          f"{frames[0][0].shape[0]}, one thread, {args.rounds} rounds x {args.passes} passes")
    print(f"attend run loop (loop_bench): median {cpp_median:.3f} ms a frame "
          f"(min {min(cpp):.3f}, max {max(cpp):.3f})")
    print(f"attend.Pipeline.process:      median {python_median:.3f} ms a frame "
          f"(min {min(python):.3f}, max {max(python):.3f})")
    print(f"Python over C++: {100.0 * (python_median / cpp_median - 1.0):+.2f} % (medians), "
          f"{100.0 * (min(python) / min(cpp) - 1.0):+.2f} % (minima)")
    overheads = plugin_overhead(frames, args.rounds)
    print(f"Python feature overhead beyond its compute: median "
          f"{1000.0 * statistics.median(overheads):.1f} us a frame "
          f"(rounds: {', '.join(f'{1000.0 * o:.1f}' for o in overheads)})")


if __name__ == "__main__":
    main()
