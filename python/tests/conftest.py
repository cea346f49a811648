"""Fixtures of the attend Python tests (docs/PYTHON.md, "Tests").

scripts/test.sh runs them with PYTHONPATH set to the build tree's python/ folder and
ATTEND_BINARY to the `attend` program of the same build, so that the module and the command
line compared here are one build.
"""

import glob
import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("ATTEND_BUILD_DIR", ROOT / "build"))
ATTEND = os.environ.get("ATTEND_BINARY", str(BUILD / "attend"))
DATA = pathlib.Path(os.environ.get("ATTEND_DATA", ROOT.parent / "shared" / "data"))


def run_attend(*args, cwd=None, check=True, env=None):
    """Runs the attend program; returns the CompletedProcess (text output)."""
    full_env = dict(os.environ)
    full_env.setdefault("ATTEND_HOME", str(ROOT))
    if env:
        full_env.update(env)
    result = subprocess.run([ATTEND, *map(str, args)], cwd=cwd, env=full_env,
                            capture_output=True, text=True, timeout=600)
    if check and result.returncode != 0:
        raise AssertionError(f"attend {' '.join(map(str, args))} exited {result.returncode}:\n"
                             f"{result.stderr}")
    return result


def records(path):
    """frames.jsonl as a list of dicts."""
    with open(path, encoding="utf-8") as file:
        return [json.loads(line) for line in file if line.strip()]


def without_timings(record):
    """A frames.jsonl record without its timings (the one part that differs run to run)."""
    return {key: value for key, value in record.items() if key != "timings_ms"}


def frame_files(sequence, side):
    return sorted(glob.glob(os.path.join(sequence, side, "*.png")))


@pytest.fixture(scope="session")
def lab(tmp_path_factory):
    """The bundled lab scene, 12 frames, rendered by attend synth: a stereo sequence folder
    with ground truth, whose targets are known by construction."""
    folder = tmp_path_factory.mktemp("lab") / "seq"
    run_attend("synth", ROOT / "sequences" / "lab.yaml", "--out", folder, "--frames", 12)
    return str(folder)


@pytest.fixture(scope="session")
def lab_frames(lab):
    """The lab sequence's frames in memory: a list of (left, right) BGR uint8 arrays."""
    import attend
    lefts = frame_files(lab, "left")
    rights = frame_files(lab, "right")
    assert len(lefts) == len(rights) == 12
    return [(attend.imread(l), attend.imread(r)) for l, r in zip(lefts, rights)]


@pytest.fixture(scope="session")
def cli_run(lab, tmp_path_factory):
    """`attend run` of the default configuration on the lab sequence, one thread, with the
    saliency and inhibition maps dumped losslessly."""
    out = tmp_path_factory.mktemp("cli") / "run"
    run_attend("run", "--sequence", lab, "--out", out, "--quiet", "--set", "threads=1",
               "--set", "output.dump=[saliency, features]", "--set", "output.map_formats=[pfm]")
    return str(out)
