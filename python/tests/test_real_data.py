"""The module on real footage from ../shared/data (skipped when it is absent): a real
pedestrian sequence through attend.Pipeline gives the records of `attend run`, with the
top-down people channel and the object files of configs/mono.yaml at work."""

import os
import re

import numpy as np
import pytest

import attend
from conftest import DATA, ROOT, run_attend

TUD = DATA / "mot" / "TUD-Campus"
TIMINGS = re.compile(r',"timings_ms":\{[^}]*\}')

pytestmark = pytest.mark.skipif(not (TUD / "left").is_dir(),
                                reason=f"reference data not found at {TUD}")


def test_a_real_pedestrian_sequence_equals_the_command_line(tmp_path):
    config = ROOT / "configs" / "mono.yaml"
    out = tmp_path / "run"
    run_attend("run", "--config", config, "--sequence", TUD, "--frames", "0:14", "--out", out,
               "--quiet", "--set", "threads=1", "--set", "output.dump=[saliency]",
               "--set", "output.map_formats=[pfm]")
    expected = (out / "frames.jsonl").read_text().splitlines()
    pipeline = attend.Pipeline(config=config, set=["threads=1"])
    labelled = 0
    for index, (left, right) in enumerate(attend.frames(TUD)):
        if index > 14:
            break
        assert right is None and left.shape == (480, 640, 3)
        result = pipeline.process(left)
        assert TIMINGS.sub("", result.record_json) == TIMINGS.sub("", expected[index])
        assert np.array_equal(result.saliency,
                              attend.read_pfm(os.path.join(out, "saliency", f"{index:06d}.pfm")))
        labelled += sum(1 for t in result.targets if t.get("label") == "person")
    # People are attended as people on this footage: the comparison is not of empty records.
    assert labelled > 0
    scores = attend.eval_run(out)
    assert scores == __import__("json").loads(run_attend("eval", out).stdout)
    assert scores["coverage"] > 0
