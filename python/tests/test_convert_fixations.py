"""scripts/convert_fixations.py (docs/FIXATIONS.md, "Dataset layout"): each format's files built
with scipy.io.savemat in the dataset's documented layout, whose fixations are known by
construction, converted and read back; bad files refused with exit 3 naming the file and the
field; bad flags with exit 2. Needs numpy and scipy only, not the module; the last test scores
a converted dataset with `attend eval-fixations` and skips when the program is not built."""

import importlib.util
import json
import os
import subprocess
import sys

import numpy as np
import pytest
from scipy.io import savemat

from conftest import ATTEND, DATA, ROOT, run_attend

SCRIPT = ROOT / "scripts" / "convert_fixations.py"
_spec = importlib.util.spec_from_file_location("convert_fixations", SCRIPT)
convert_fixations = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(convert_fixations)


def convert(*args):
    """Runs the script as a user would; returns the CompletedProcess."""
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True,
                          text=True, timeout=300)


def read_fixations(path):
    """A converted fixation file: its header line and its rows as tuples of numbers."""
    lines = path.read_text(encoding="utf-8").splitlines()
    assert lines[0].startswith("# subject x y")
    rows = [tuple(float(v) for v in line.split()) for line in lines[1:]]
    return lines[0], rows


def touch(path, content=b"stimulus"):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(content)
    return path


def cells(items):
    """A MATLAB cell array (a column) of the given values."""
    array = np.empty((len(items), 1), dtype=object)
    for i, item in enumerate(items):
        array[i, 0] = item
    return array


# ---------------------------------------------------------------------------------------------
# The saccade rule of MIT1003 on constructed eye traces

RULE = convert_fixations.SaccadeRule()
HZ = RULE.sampling_hz


def hold(x, y, samples):
    """A fixation: jitter of 0, +0.3, -0.3 px around (x, y), whose median is (x, y) for any
    run of at least 3 of its samples."""
    jitter = np.array([0.0, 0.3, -0.3])[np.arange(samples) % 3]
    return np.column_stack([x + jitter, y - jitter])


def jump(start, end, samples):
    """A saccade: `samples` evenly spaced positions strictly between start and end."""
    t = np.arange(1, samples + 1)[:, None] / (samples + 1)
    return np.asarray(start) + t * (np.asarray(end) - np.asarray(start))


def test_saccade_rule_defaults_are_valid_and_a_bad_field_is_named():
    assert RULE.check() is None
    bad = convert_fixations.SaccadeRule(window=0)
    assert "window" in bad.check()


def test_saccade_rule_finds_each_constructed_fixation_in_order():
    # The centre cross, then three fixations, with 8-sample saccades between them.
    plan = [((512, 384), 80), ((300, 200), 100), ((600, 400), 150), ((160, 100), 120)]
    parts, starts = [], []
    for k, (position, samples) in enumerate(plan):
        if k:
            parts.append(jump(plan[k - 1][0], position, 8))
        starts.append(sum(len(p) for p in parts))
        parts.append(hold(*position, samples))
    found = convert_fixations.detect_fixations(np.vstack(parts))
    assert [tuple(row[:2]) for row in found] == [p for p, _ in plan]
    for row, start, (_, samples) in zip(found, starts, plan):
        # Each fixation loses at most the velocity windows (window + 2 samples) at each end.
        slack_ms = 1000.0 * 2 * (RULE.window + 2) / HZ
        assert samples * 1000 / HZ - slack_ms <= row[3] <= samples * 1000 / HZ
        assert start * 1000 / HZ <= row[2] <= start * 1000 / HZ + slack_ms


def test_a_fixation_under_50_ms_between_saccades_joins_them_and_a_blink_splits_one():
    trace = np.vstack([hold(100, 100, 90), jump((100, 100), (400, 300), 8),
                       hold(400, 300, 6),  # 25 ms: no fixation
                       jump((400, 300), (200, 500), 8), hold(200, 500, 60),
                       np.full((30, 2), -1.0),  # a blink: negative positions
                       hold(200, 500, 60)])
    found = convert_fixations.detect_fixations(trace)
    assert [tuple(row[:2]) for row in found] == [(100, 100), (200, 500), (200, 500)]
    # The blink's samples belong to neither fixation: the second starts after it.
    blink_end_ms = 1000.0 * (90 + 8 + 6 + 8 + 60 + 30) / HZ
    assert found[2][2] >= blink_end_ms


def test_a_still_recording_is_one_fixation_and_an_empty_one_none():
    found = convert_fixations.detect_fixations(hold(50, 60, 200))
    assert found.tolist() == [[50.0, 60.0, 0.0, 1000.0 * 200 / HZ]]
    assert convert_fixations.detect_fixations(np.zeros((0, 2))).shape == (0, 4)


# ---------------------------------------------------------------------------------------------
# MIT1003: ALLSTIMULI/<image>.jpeg, DATA/<subject>/<image>.mat

MIT_PLAN = {  # image -> subject -> fixations after the centre cross, each (x, y, samples)
    "i1": {"CNG": [(300, 200, 100), (600, 400, 150)], "ajs": [(50, 60, 120)]},
    "i2": {"ajs": [(700, 100, 90), (10, 20, 100), (400, 300, 80)]},
}


def mit_trace(fixations):
    parts, last = [hold(512, 384, 80)], (512, 384)
    for x, y, samples in fixations:
        parts += [jump(last, (x, y), 8), hold(x, y, samples)]
        last = (x, y)
    return np.vstack(parts)


def save_mit(path, name, eye_data):
    path.parent.mkdir(parents=True, exist_ok=True)
    savemat(path, {name: {"DATA": {"eyeData": eye_data}, "imgName": name + ".jpeg"}})


@pytest.fixture
def mit_source(tmp_path):
    src = tmp_path / "mit"
    for image, subjects in MIT_PLAN.items():
        touch(src / "ALLSTIMULI" / f"{image}.jpeg", image.encode())
        for subject, fixations in subjects.items():
            save_mit(src / "DATA" / subject / f"{image}.mat", image, mit_trace(fixations))
    touch(src / "ALLSTIMULI" / "i3.jpeg")  # nobody's data: skipped
    savemat(src / "DATA" / "ajs" / "CalibrationData.mat", {"calib": np.eye(2)})
    return src


def test_mit1003_fixations_per_subject_in_order_without_the_centre_one(mit_source, tmp_path):
    out = tmp_path / "dataset"
    result = convert("--format", "mit1003", mit_source, "--out", out)
    assert result.returncode == 0, result.stderr
    assert "i3.jpeg: no subject's data" in result.stderr
    assert sorted(p.name for p in (out / "stimuli").iterdir()) == ["i1.jpeg", "i2.jpeg"]
    assert (out / "stimuli" / "i1.jpeg").read_bytes() == b"i1"
    subjects = {"CNG": 0, "ajs": 1}  # sorted folder names
    for image, plan in MIT_PLAN.items():
        header, rows = read_fixations(out / "fixations" / f"{image}.txt")
        assert "0 CNG, 1 ajs" in header and "without the first" in header
        expected = [(subjects[s], x, y) for s in sorted(plan) for x, y, _ in plan[s]]
        assert [row[:3] for row in rows] == expected
        durations = [n * 1000 / HZ for s in sorted(plan) for _, _, n in plan[s]]
        for row, duration in zip(rows, durations):
            assert duration - 1000.0 * 2 * (RULE.window + 2) / HZ <= row[3] <= duration + 0.05


def test_mit1003_keep_first_keeps_the_centre_fixation(mit_source, tmp_path):
    out = tmp_path / "dataset"
    result = convert("--format", "mit1003", mit_source, "--out", out, "--keep-first")
    assert result.returncode == 0, result.stderr
    _, rows = read_fixations(out / "fixations" / "i2.txt")
    assert [row[:3] for row in rows] == [(1, 512, 384), (1, 700, 100), (1, 10, 20), (1, 400, 300)]


# ---------------------------------------------------------------------------------------------
# OSIE and Saliency in Crowd: data/eye/fixations.mat, data/stimuli/

NUS_PLAN = [  # (img, [subject: (fix_x, fix_y, fix_duration) or None for an empty cell])
    ("1001.jpg", [([10.5, 200, 30], [20, 40.25, 60], [150, 300, 210]),
                  ([5], [6], [7]),  # one fixation: MATLAB's 1x1, scipy's scalar
                  None,
                  ([], [], [])]),
    ("1002.jpg", [([700], [500], [90]), ([1, 2], [3, 4], [100, 200])]),
    ("1003.jpg", [([1], [1], [1])]),  # no stimulus file: skipped
    ("1004.jpg", [None, ([], [], [])]),  # nobody's fixations: skipped
]


def nus_struct(plan):
    images = []
    for name, subjects in plan:
        observers = []
        for subject in subjects:
            if subject is None:
                observers.append(np.zeros((0, 0)))
                continue
            xs, ys, ds = (np.array([values], dtype=float).reshape(1, -1) for values in subject)
            observers.append({"fix_x": xs, "fix_y": ys, "fix_duration": ds})
        images.append({"img": name, "subjects": cells(observers)})
    return cells(images)


def nus_source(root, plan=NUS_PLAN, fixations=None):
    data = root / "data"
    for name, _ in plan[:2]:
        touch(data / "stimuli" / name, name.encode())
    (data / "eye").mkdir(parents=True, exist_ok=True)
    savemat(data / "eye" / "fixations.mat",
            {"fixations": nus_struct(plan) if fixations is None else fixations})
    return root


@pytest.mark.parametrize("fmt", ["osie", "crowd"])
def test_nus_fixations_keep_subjects_order_and_durations(fmt, tmp_path):
    src, out = nus_source(tmp_path / "src"), tmp_path / "dataset"
    result = convert("--format", fmt, src, "--out", out)
    assert result.returncode == 0, result.stderr
    assert "1003.jpg: no stimulus" in result.stderr
    assert "1004.jpg: no subject's fixations" in result.stderr
    assert "2 stimuli" in result.stdout and "2 skipped" in result.stdout
    for name, subjects in NUS_PLAN[:2]:
        header, rows = read_fixations(out / "fixations" / (name[:-4] + ".txt"))
        assert header.startswith("# subject x y duration_ms")
        expected = [(j, x, y, d) for j, s in enumerate(subjects) if s for x, y, d in zip(*s)]
        assert rows == expected
    assert (out / "stimuli" / "1002.jpg").read_bytes() == b"1002.jpg"


def test_symlink_links_the_stimuli_and_overwrite_replaces_a_dataset(tmp_path):
    src, out = nus_source(tmp_path / "src"), tmp_path / "dataset"
    touch(out / "fixations" / "stale.txt")
    refused = convert("--format", "osie", src, "--out", out)
    assert refused.returncode == 2 and "--overwrite" in refused.stderr
    result = convert("--format", "osie", src, "--out", out, "--symlink", "--overwrite")
    assert result.returncode == 0, result.stderr
    link = out / "stimuli" / "1001.jpg"
    assert link.is_symlink() and link.resolve() == (src / "data/stimuli/1001.jpg").resolve()
    assert not (out / "fixations" / "stale.txt").exists()


def crowd200_ids():
    folder = DATA / "fixations" / "crowd200" / "fixations"
    return sorted(p.stem for p in folder.glob("*.txt"))[:5] if folder.is_dir() else []


@pytest.mark.skipif(not crowd200_ids(), reason="../shared/data/fixations/crowd200 is absent")
def test_crowd200_in_a_fixations_mat_converts_back_to_the_same_lines(tmp_path):
    """../shared/data's crowd200 (converted from Saliency in Crowd's fixations.mat elsewhere):
    its fixations put back into a fixations.mat of the dataset's layout convert to the same
    columns, subjects and numbers."""
    shared = DATA / "fixations" / "crowd200"
    plan = []
    for image in crowd200_ids():
        lines = (shared / "fixations" / f"{image}.txt").read_text().splitlines()
        assert lines[0].startswith("# subject x y duration_ms")
        rows = np.array([[float(v) for v in line.split()] for line in lines[1:]])
        subjects = [None] * (int(rows[:, 0].max()) + 1)
        for j in range(len(subjects)):
            mine = rows[rows[:, 0] == j]
            subjects[j] = (mine[:, 1], mine[:, 2], mine[:, 3]) if len(mine) else None
        plan.append((f"{image}.jpg", subjects, rows))
    src = tmp_path / "crowd"
    for name, _, _ in plan:
        os.makedirs(src / "data" / "stimuli", exist_ok=True)
        os.symlink(shared / "stimuli" / name, src / "data" / "stimuli" / name)
    nus_source(src, plan=[], fixations=nus_struct([(n, s) for n, s, _ in plan]))
    out = tmp_path / "dataset"
    result = convert("--format", "crowd", src, "--out", out)
    assert result.returncode == 0, result.stderr
    for name, _, rows in plan:
        header, converted = read_fixations(out / "fixations" / (name[:-4] + ".txt"))
        assert header.split("(")[0].split() == ["#", "subject", "x", "y", "duration_ms"]
        np.testing.assert_allclose(np.array(converted), rows, atol=1e-9)


# ---------------------------------------------------------------------------------------------
# CAT2000: Stimuli/<Category>/<image>.jpg, FIXATIONLOCS/<Category>/<image>.mat

def test_cat2000_binary_maps_become_subject_0_per_fixated_pixel(tmp_path):
    src, out = tmp_path / "trainSet", tmp_path / "dataset"
    fixated = {("Action", "001"): [(2, 5), (0, 0), (3, 1)],  # (row, column), 0-based
               ("Art", "001"): [(4, 6)]}
    for (category, image), pixels in fixated.items():
        touch(src / "Stimuli" / category / f"{image}.jpg", f"{category}{image}".encode())
        locations = np.zeros((5, 8), dtype=np.uint8)
        for row, column in pixels:
            locations[row, column] = 1
        (src / "FIXATIONLOCS" / category).mkdir(parents=True, exist_ok=True)
        savemat(src / "FIXATIONLOCS" / category / f"{image}.mat", {"fixLocs": locations})
    touch(src / "Stimuli" / "Action" / "Output" / "001.jpg")  # not a stimulus
    touch(src / "Stimuli" / "Art" / "002.jpg")  # no map: skipped
    touch(src / "Stimuli" / "Art" / "003.jpg")  # an empty map: skipped
    savemat(src / "FIXATIONLOCS" / "Art" / "003.mat", {"fixLocs": np.zeros((5, 8))})
    result = convert("--format", "cat2000", tmp_path, "--out", out)
    assert result.returncode == 0, result.stderr
    assert "Art/002.jpg: no" in result.stderr and "Art/003.jpg: no fixated pixel" in result.stderr
    assert sorted(p.name for p in (out / "stimuli").iterdir()) == ["Action_001.jpg",
                                                                  "Art_001.jpg"]
    for (category, image), pixels in fixated.items():
        header, rows = read_fixations(out / "fixations" / f"{category}_{image}.txt")
        assert header.startswith("# subject x y  (") and "subject 0" in header
        assert rows == [(0, column + 1, row + 1) for row, column in sorted(pixels)]


# ---------------------------------------------------------------------------------------------
# Bad input: exit 3, the file and the field named, no traceback

def bad_osie(root, subject):
    """An OSIE source whose one image has a good first subject and `subject` second."""
    return nus_source(root, fixations=cells([{"img": "1001.jpg", "subjects": cells(
        [{"fix_x": [[1.0]], "fix_y": [[1.0]], "fix_duration": [[1.0]]}, subject])}]))


def osie_without_fixations_variable(root):
    nus_source(root)
    savemat(root / "data" / "eye" / "fixations.mat", {"fix": np.eye(2)})
    return root


def bad_mit(root, content):
    touch(root / "ALLSTIMULI" / "i1.jpeg")
    (root / "DATA" / "hp").mkdir(parents=True)
    savemat(root / "DATA" / "hp" / "i1.mat", content)
    return root


def bad_cat2000(root, content):
    touch(root / "Stimuli" / "Indoor" / "001.jpg")
    (root / "FIXATIONLOCS" / "Indoor").mkdir(parents=True)
    savemat(root / "FIXATIONLOCS" / "Indoor" / "001.mat", content)
    return root


def cat2000_not_matlab(root):
    bad_cat2000(root, {"fixLocs": np.ones((2, 2))})
    (root / "FIXATIONLOCS" / "Indoor" / "001.mat").write_bytes(b"MATLAB 5.0 MAT-file, junk")
    return root


def mit_without_stimuli(root):
    touch(root / "DATA" / "hp" / "i1.mat")
    return root


BAD_INPUTS = {  # case: (format, source builder, what the message must say)
    "fix_y shorter": ("osie", lambda r: bad_osie(r, {
        "fix_x": [[1.0, 2.0]], "fix_y": [[1.0]], "fix_duration": [[1.0, 2.0]]}),
        "fixations.mat: fixations{1}.subjects{2}.fix_y: 1 values, fix_x has 2"),
    "no fix_duration": ("crowd", lambda r: bad_osie(r, {"fix_x": [[1.0]], "fix_y": [[1.0]]}),
                        "fixations.mat: fixations{1}.subjects{2}.fix_duration: missing"),
    "NaN fix_x": ("osie", lambda r: bad_osie(r, {
        "fix_x": [[1.0, np.nan]], "fix_y": [[1.0, 2.0]], "fix_duration": [[1.0, 2.0]]}),
        "fixations{1}.subjects{2}.fix_x(2): not a finite number"),
    "text fix_y": ("osie", lambda r: bad_osie(r, {
        "fix_x": [[1.0]], "fix_y": "left", "fix_duration": [[1.0]]}),
        "fixations{1}.subjects{2}.fix_y: expected numbers"),
    "no img": ("osie", lambda r: nus_source(r, fixations=cells([{"subjects": cells([])}])),
               "fixations.mat: fixations{1}.img: missing"),
    "no fixations variable": ("osie", osie_without_fixations_variable,
                              "fixations.mat: fixations: missing"),
    "eyeData one column": ("mit1003", lambda r: bad_mit(r, {
        "i1": {"DATA": {"eyeData": np.ones((30, 1))}}}),
        "i1.mat: i1.DATA(1).eyeData: expected N x 2 eye positions, got 30 values"),
    "eyeData three-dimensional": ("mit1003", lambda r: bad_mit(r, {
        "i1": {"DATA": {"eyeData": np.ones((30, 2, 2))}}}),
        "i1.mat: i1.DATA(1).eyeData: expected N x 2 eye positions, got shape 30x2x2"),
    "no DATA": ("mit1003", lambda r: bad_mit(r, {"i1": {"eye": np.ones((30, 2))}}),
                "i1.mat: i1.DATA: missing"),
    "no MIT layout": ("mit1003", mit_without_stimuli, "no ALLSTIMULI/ folder"),
    "fixLocs 3-D": ("cat2000", lambda r: bad_cat2000(r, {"fixLocs": np.ones((2, 3, 3))}),
                    "001.mat: fixLocs: expected a 2-D binary map"),
    "not MATLAB": ("cat2000", cat2000_not_matlab, "001.mat: not a readable MATLAB file"),
}


@pytest.mark.parametrize("case", sorted(BAD_INPUTS))
def test_bad_input_is_refused_naming_file_and_field(case, tmp_path):
    fmt, build, message = BAD_INPUTS[case]
    src = build(tmp_path / "src")
    result = convert("--format", fmt, src, "--out", tmp_path / "dataset")
    assert result.returncode == 3, (result.returncode, result.stderr)
    assert message in result.stderr
    assert result.stderr.startswith("convert_fixations: error: ")
    assert "Traceback" not in result.stderr


@pytest.mark.parametrize("args", [
    ["--format", "osie", "SRC"],                             # no --out
    ["SRC", "--out", "OUT"],                                 # no --format
    ["--format", "salicon", "SRC", "--out", "OUT"],          # not a format
    ["--format", "osie", "SRC", "--out", "OUT", "--fast"],   # not a flag
    ["--format", "osie", "SRC", "--out", "OUT", "--keep-first"],  # MIT1003's flag only
])
def test_bad_flags_exit_2(args, tmp_path):
    src = nus_source(tmp_path / "src")
    args = [str(src) if a == "SRC" else str(tmp_path / "out") if a == "OUT" else a for a in args]
    result = convert(*args)
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr


def test_a_missing_source_is_bad_input(tmp_path):
    result = convert("--format", "cat2000", tmp_path / "nothing", "--out", tmp_path / "out")
    assert result.returncode == 3 and "nothing: no such folder" in result.stderr


# ---------------------------------------------------------------------------------------------
# The converted dataset as attend eval-fixations reads it

def write_pgm(path, width, height):
    path.parent.mkdir(parents=True, exist_ok=True)
    pixels = (np.arange(width * height) % 251).astype(np.uint8)
    path.write_bytes(b"P5\n%d %d\n255\n" % (width, height) + pixels.tobytes())


def write_pfm(path, image):
    """A grey PFM: little-endian floats, bottom row first."""
    path.parent.mkdir(parents=True, exist_ok=True)
    height, width = image.shape
    data = np.ascontiguousarray(image[::-1], dtype="<f4").tobytes()
    path.write_bytes(b"Pf\n%d %d\n-1.0\n" % (width, height) + data)


@pytest.mark.skipif(not os.path.exists(ATTEND), reason=f"{ATTEND} is not built")
def test_converted_fixations_land_on_their_pixels_in_eval_fixations(tmp_path):
    """A map that is 1 exactly at the constructed fixations' pixels (x, y 1-based in the file,
    so [y - 1, x - 1]) and 0 elsewhere scores AUC-Judd 1 and a large NSS; the same map moved
    one pixel right scores below chance: the converted coordinates are read where they were
    put, neither swapped nor shifted."""
    width, height = 40, 30
    plan = [("1001.jpg", [([3, 17.4, 38], [5, 9, 28.2], [100, 200, 300]),
                          ([25], [12], [150])]),
            ("1002.jpg", [([1, 40], [1, 30], [80, 90])])]
    src = tmp_path / "osie"
    for name, _ in plan:  # PGM content behind a .jpg name is not what attend reads: use .pgm
        write_pgm(src / "data" / "stimuli" / name.replace(".jpg", ".pgm"), width, height)
    nus_source(src, plan=[], fixations=nus_struct(
        [(name.replace(".jpg", ".pgm"), subjects) for name, subjects in plan]))
    dataset = tmp_path / "dataset"
    result = convert("--format", "osie", src, "--out", dataset)
    assert result.returncode == 0, result.stderr
    for name, subjects in plan:
        oracle = np.zeros((height, width), dtype=np.float32)
        for xs, ys, _ in subjects:
            for x, y in zip(xs, ys):
                oracle[int(round(y)) - 1, int(round(x)) - 1] = 1.0
        write_pfm(tmp_path / "oracle" / (name[:-4] + ".pfm"), oracle)
        write_pfm(tmp_path / "shifted" / (name[:-4] + ".pfm"), np.roll(oracle, 1, axis=1))
    out = tmp_path / "scores"
    run_attend("eval-fixations", f"oracle={tmp_path / 'oracle'}",
               f"shifted={tmp_path / 'shifted'}", "--dataset", dataset, "--max-side", 0,
               "--sigma", 1, "--out", out, "--quiet")
    methods = json.loads((out / "fixations.json").read_text())["methods"]
    assert methods["oracle"]["images"] == 2 and methods["shifted"]["images"] == 2
    assert methods["oracle"]["auc_judd"]["mean"] == 1.0
    assert methods["oracle"]["nss"]["mean"] > 5
    assert methods["shifted"]["nss"]["mean"] < 0
    assert methods["shifted"]["auc_judd"]["mean"] < 0.6
