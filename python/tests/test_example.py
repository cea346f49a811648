"""The example a researcher copies (examples/python/) runs and writes its figure."""

import os
import subprocess
import sys

from conftest import ROOT


def test_the_example_runs_scores_and_writes_its_figure(lab, tmp_path):
    figure = tmp_path / "figure.png"
    result = subprocess.run(
        [sys.executable, str(ROOT / "examples" / "python" / "attend_example.py"), lab,
         "--frames", "0:7", "--show", "2", "--out", str(figure)],
        cwd=tmp_path, env=dict(os.environ), capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    assert "scores:" in result.stdout and "MOT at IoU 0.5" in result.stdout
    with open(figure, "rb") as file:
        assert file.read(8) == b"\x89PNG\r\n\x1a\n"
    assert os.path.getsize(figure) > 10000
    # The run folder records the Python plugin, so that attend run --config repeats it.
    with open(tmp_path / "figure-run" / "config.yaml", encoding="utf-8") as file:
        assert "motion_energy.py" in file.read()
