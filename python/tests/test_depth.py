"""The targets' depth in the Python module (issue 44, SPEC 3.3): disparity_px, position_m and
their standard deviations in the records attend.read_run and Pipeline.process give, the depth
columns of Run.targets_frame(), and a Pipeline given a stereo camera (focal_px, baseline_m,
principal_point)."""

import json
import math

import pytest

import attend

# A stereo run's records written by hand: frame 0 has a target with a position and one with
# a disparity only (no calibration for it), frame 1 an occluded target (no depth) and a
# position with an unknown standard deviation (null), frame 2 is a record of before issue 44.
RECORDS = [
    {"frame": 0, "targets": [
        {"id": 1, "bbox": [10, 20, 30, 40], "area": 900, "saliency": 0.5, "state": "new",
         "kind": "object", "similarity": "hsv", "tracker": "bip", "disparity_px": 12.0,
         "disparity_sd_px": 0.25, "position_m": [-0.5, 0.25, 3.0],
         "position_sd_m": [0.01, 0.02, 0.0625]},
        {"id": 2, "bbox": [60, 20, 10, 10], "area": 80, "saliency": 0.25, "state": "new",
         "kind": "object", "similarity": "hsv", "tracker": "bip", "disparity_px": 4.5,
         "disparity_sd_px": None}],
     "new": [1, 2], "timings_ms": {"segment": 1.0}},
    {"frame": 1, "targets": [
        {"id": 1, "bbox": [12, 20, 30, 40], "area": 900, "saliency": 0.5, "state": "tracked",
         "kind": "object", "similarity": "hsv", "tracker": "bip", "disparity_px": 9.0,
         "disparity_sd_px": 0.5, "position_m": [-0.4, 0.25, 4.0],
         "position_sd_m": [None, None, 0.2]},
        {"id": 2, "bbox": [60, 20, 10, 10], "area": 80, "saliency": 0.25, "state": "occluded",
         "kind": "object", "similarity": "hsv", "tracker": "bip"}],
     "new": [], "timings_ms": {"segment": 1.0}},
    {"frame": 2, "targets": [
        {"id": 1, "bbox": [14, 20, 30, 40], "area": 900, "saliency": 0.5, "state": "tracked",
         "kind": "object", "similarity": "hsv"}],
     "new": [], "timings_ms": {"segment": 1.0}},
]


@pytest.fixture
def depth_run(tmp_path):
    folder = tmp_path / "run"
    folder.mkdir()
    with open(folder / "frames.jsonl", "w", encoding="utf-8") as file:
        for record in RECORDS:
            file.write(json.dumps(record) + "\n")
    return folder


def test_read_run_gives_each_targets_depth_as_recorded(depth_run):
    run = attend.read_run(depth_run)
    first = run.frames[0]["targets"]
    assert first[0]["disparity_px"] == 12.0
    assert first[0]["position_m"] == [-0.5, 0.25, 3.0]
    assert first[0]["position_sd_m"] == [0.01, 0.02, 0.0625]
    assert first[1]["disparity_px"] == 4.5 and "position_m" not in first[1]
    # An older record, and an occluded target, have none.
    assert "disparity_px" not in run.frames[2]["targets"][0]
    assert "disparity_px" not in run.frames[1]["targets"][1]


def test_target_rows_split_the_position_into_coordinates(depth_run):
    rows = attend.read_run(depth_run).target_rows()
    assert len(rows) == 5
    first = rows[0]
    assert (first["x_m"], first["y_m"], first["z_m"]) == (-0.5, 0.25, 3.0)
    assert (first["x_sd_m"], first["y_sd_m"], first["z_sd_m"]) == (0.01, 0.02, 0.0625)
    assert "position_m" not in first and "position_sd_m" not in first
    assert rows[1]["disparity_px"] == 4.5 and rows[1]["disparity_sd_px"] is None
    assert rows[1]["z_m"] is None
    assert rows[3]["disparity_px"] is None  # occluded
    assert rows[4]["disparity_px"] is None and rows[4]["z_m"] is None  # an older record


def test_targets_frame_has_the_depth_columns(depth_run, tmp_path):
    pandas = pytest.importorskip("pandas")
    table = attend.read_run(depth_run).targets_frame()
    for column in ("disparity_px", "disparity_sd_px", "x_m", "y_m", "z_m", "x_sd_m", "y_sd_m",
                   "z_sd_m"):
        assert column in table.columns
        assert table[column].dtype == float, column
    one = table[table.id == 1].set_index("frame")
    assert list(one.z_m.iloc[:2]) == [3.0, 4.0]
    assert math.isnan(one.z_m.loc[2])
    assert math.isnan(one.x_sd_m.loc[1]) and one.z_sd_m.loc[1] == 0.2
    assert table.z_m.mean() == pytest.approx(3.5)
    assert table.disparity_px.count() == 3
    # A run without targets still has the columns.
    empty = tmp_path / "empty"
    empty.mkdir()
    (empty / "frames.jsonl").write_text(
        json.dumps({"frame": 0, "targets": [], "new": [], "timings_ms": {}}) + "\n")
    assert isinstance(attend.read_run(empty).targets_frame(), pandas.DataFrame)
    assert "z_m" in attend.read_run(empty).targets_frame().columns


def lab_pipeline(**camera):
    return attend.Pipeline(set=["threads=1", "sequence.width=160"], **camera)


def seen(result):
    return [t for t in result.targets if t["state"] in ("new", "tracked", "resumed")]


def test_a_pipeline_with_a_camera_gives_positions(lab_frames):
    # The lab scene's camera: focal length 300 px, baseline 0.12 m (sequences/lab.yaml), for the
    # 320 x 240 frames handed in; the pipeline works at 160 x 120, and the records are in the
    # input's pixels, so Z = 300 * 0.12 / disparity_px there.
    plain = lab_pipeline()
    placed = lab_pipeline(focal_px=300, baseline_m=0.12)
    shifted = lab_pipeline(focal_px=300, baseline_m=0.12, principal_point=(169.5, 119.5))
    positions = 0
    for left, right in lab_frames[:6]:
        without = plain.process(left, right)
        result = placed.process(left, right)
        moved = shifted.process(left, right)
        for bare, target, other in zip(seen(without), seen(result), seen(moved)):
            assert "disparity_px" in bare and "position_m" not in bare
            assert target["disparity_px"] == bare["disparity_px"]
            if "position_m" not in target:
                continue
            positions += 1
            x, y, z = target["position_m"]
            assert z == pytest.approx(36.0 / target["disparity_px"], rel=1e-3)
            assert target["position_sd_m"][2] > 0
            # The principal point 10 px further right puts the target 10 Z / f further left.
            assert other["position_m"][0] == pytest.approx(x - 10 * z / 300, abs=2e-4)
            assert other["position_m"][1] == pytest.approx(y, abs=1e-4)
    assert positions >= 6
    calibration = placed.info["calibration"]
    assert calibration["focal_px"] == 300 and calibration["baseline_m"] == pytest.approx(0.12)
    assert calibration["principal_point"] == (159.5, 119.5)
    assert shifted.info["calibration"]["principal_point"] == (169.5, 119.5)
    assert plain.info["calibration"] is None


def test_a_camera_needs_both_numbers_and_a_stereo_pair(lab_frames):
    with pytest.raises(attend.ConfigError, match="focal_px and baseline_m"):
        attend.Pipeline(focal_px=300)
    with pytest.raises(attend.ConfigError, match="principal_point"):
        attend.Pipeline(principal_point=(1, 2))
    with pytest.raises(attend.ConfigError, match="focal_px"):
        attend.Pipeline(focal_px=-1, baseline_m=0.1)
    with pytest.raises(attend.ConfigError, match="baseline_m"):
        attend.Pipeline(focal_px=300, baseline_m=0)
    # Monocular frames: no disparity, no position.
    mono = attend.Pipeline(config={"features": [{"name": "colour_contrast"}]}, focal_px=300,
                           baseline_m=0.12)
    for left, _ in lab_frames[:3]:
        for target in mono.process(left).targets:
            assert "disparity_px" not in target and "position_m" not in target
    assert mono.info["calibration"] is None
