"""attend.read_run on damaged run folders (issue 46, case 4): every frames.jsonl line is read
by the command line's reader first, so what `attend eval` refuses read_run refuses with the
same message; the run's other files, damaged or not files at all, are InputErrors naming them."""

import json
import os
import shutil

import pytest

import attend
from conftest import run_attend


@pytest.fixture
def run_copy(cli_run, tmp_path):
    """A copy of the command line's run folder (its records, summary, scan path and
    configuration; not its dumped maps), to damage."""
    folder = tmp_path / "run"
    shutil.copytree(cli_run, folder, ignore=shutil.ignore_patterns("features", "saliency"))
    return folder


def first_record(folder, change):
    """Rewrites frames.jsonl with change(record) applied to its first record."""
    path = folder / "frames.jsonl"
    lines = path.read_text().splitlines()
    record = json.loads(lines[0])
    change(record)
    lines[0] = json.dumps(record)
    path.write_text("\n".join(lines) + "\n")
    return f"{path}:1: "


def read_all(folder):
    """read_run and every method of the Run that reads the records."""
    run = attend.read_run(folder)
    run.target_rows()
    run.targets_frame()
    run.frames_frame()
    return run


# Records the command line refuses: read_run refuses them with attend eval's message.
REFUSED_BY_EVAL = {
    "frame a string": (lambda r: r.update(frame="2"), "('frame' is not an integer)"),
    "frame negative": (lambda r: r.update(frame=-1), "('frame' out of range"),
    "a box of three": (lambda r: r["targets"][0].update(bbox=[1, 2, 3]), "bbox needs 4 numbers"),
    "an unknown state": (lambda r: r["targets"][0].update(state="lost?"), "unknown state"),
    "no timings": (lambda r: r.pop("timings_ms"), "not a frame record"),
    "an id of text": (lambda r: r["targets"][0].update(id="1"), "('id' is not an integer)"),
    "a target twice": (lambda r: r["targets"].append(dict(r["targets"][0])),
                       "twice (targets 1 and "),
    "targets a map": (lambda r: r.update(targets={"a": 1}), "('targets' is not a list)"),
}


@pytest.mark.parametrize("name", sorted(REFUSED_BY_EVAL))
def test_read_run_refuses_what_attend_eval_refuses_with_its_message(run_copy, name):
    change, reason = REFUSED_BY_EVAL[name]
    where = first_record(run_copy, change)
    with pytest.raises(attend.InputError) as error:
        read_all(run_copy)
    message = str(error.value)
    assert message.startswith(where + "not a frame record") and reason in message
    assert error.value.status == 3
    evaluated = run_attend("eval", run_copy, check=False)
    assert evaluated.returncode == 3, evaluated.stderr
    assert f"attend: error: {message}" in evaluated.stderr


def test_binary_garbage_in_frames_jsonl_is_an_input_error_naming_file_and_line(run_copy):
    path = run_copy / "frames.jsonl"
    lines = path.read_bytes().split(b"\n")
    lines[3] = bytes(range(256)).replace(b"\n", b"")
    path.write_bytes(b"\n".join(lines))
    with pytest.raises(attend.InputError, match=f"^{path}:4: not a frame record"):
        read_all(run_copy)
    # A string of bad UTF-8 inside valid JSON is refused as well (it raised
    # UnicodeDecodeError).
    path.write_bytes(b'{"frame": 0, "targets": [], "new": [], "timings_ms": {"\xff": 1}}\n')
    with pytest.raises(attend.InputError, match=f"^{path}:1: not a frame record"):
        read_all(run_copy)


@pytest.mark.parametrize("change, reason", [
    (lambda r: r.update(targets={"a": r["targets"][0]}), "'targets' is not a list"),
    (lambda r: r.update(timings_ms=[1.0, 2.0]), "'timings_ms' is not a map"),
    (lambda r: r.update(timings_ms=3.0), "'timings_ms' is not a map"),
])
def test_records_the_runs_methods_cannot_read_are_refused(run_copy, change, reason):
    # A map of targets passed read_run and then made targets_frame() raise AttributeError.
    where = first_record(run_copy, change)
    with pytest.raises(attend.InputError) as error:
        read_all(run_copy)
    assert str(error.value).startswith(where + "not a frame record (" + reason)


@pytest.mark.parametrize("name, content, reason", [
    ("summary.json", b"\xff\xfe\x00\x01garbage", "not UTF-8 text (byte 1"),
    ("summary.json", b'{"frames": 12,', "not a JSON object (JSONDecodeError"),
    ("summary.json", b"[1, 2]", "not a JSON object (it is a list)"),
    ("summary.json", b'{"fps": NaN}', "NaN is not JSON"),
    ("summary.json", b"[" * 100000 + b"]" * 100000, "not a JSON object (RecursionError"),
    ("scanpath.json", b'{"frame": 0}', "not a JSON list (it is an object)"),
    ("scanpath.json", os.urandom(64) + b"\xff", "not UTF-8 text"),
    ("config.yaml", b"\x00\xff\xd8\xff binary", "not valid UTF-8"),
    ("config.yaml", b"features: [1, 2\nsequence: {", "YAML syntax error"),
    ("config.yaml", b"a: 1\na: 2\n", "a"),
])
def test_a_damaged_summary_scanpath_or_configuration_is_an_input_error_naming_it(
        run_copy, name, content, reason):
    path = run_copy / name
    path.write_bytes(content)
    with pytest.raises(attend.InputError) as error:
        read_all(run_copy)
    assert str(error.value).startswith(str(path)) and reason in str(error.value)


@pytest.mark.parametrize("name", ["frames.jsonl", "summary.json", "scanpath.json",
                                  "config.yaml"])
@pytest.mark.parametrize("kind", ["folder", "fifo", "device"])
def test_a_run_file_that_is_no_regular_file_is_an_input_error(run_copy, name, kind):
    path = run_copy / name
    os.remove(path)
    if kind == "folder":
        os.mkdir(path)
    elif kind == "fifo":
        os.mkfifo(path)  # reading it would block for ever
    else:
        os.symlink("/dev/zero", path)  # reading it would never end
    with pytest.raises(attend.InputError) as error:
        read_all(run_copy)
    expected = "is a folder, not a file" if kind == "folder" else "is not a regular file ("
    assert str(error.value).startswith(f"{path}: {expected}")


def test_a_valid_run_reads_as_before(run_copy):
    # The dicts are JSON's, line by line; a run without its optional files still reads.
    lines = (run_copy / "frames.jsonl").read_text().splitlines()
    run = read_all(run_copy)
    assert run.frames == [json.loads(line) for line in lines]
    assert run.summary == json.loads((run_copy / "summary.json").read_text())
    assert run.scanpath == json.loads((run_copy / "scanpath.json").read_text())
    assert run.config == (run_copy / "config.yaml").read_text()
    for name in ("summary.json", "scanpath.json", "config.yaml"):
        os.remove(run_copy / name)
    run = read_all(run_copy)
    assert (run.summary, run.scanpath, run.config) == ({}, [], "")
    with pytest.raises(attend.InputError, match="not a run folder"):
        attend.read_run(run_copy / "nothing")
