"""The stages on numpy arrays, the run readers and the evaluation functions, on inputs whose
answers are known by construction, and their errors."""

import json
import os

import numpy as np
import pytest

import attend
from conftest import records, run_attend


def quadrants(height=64, width=80):
    """Four flat colour quadrants: four regions, each a quarter of the image."""
    image = np.zeros((height, width, 3), np.uint8)
    h, w = height // 2, width // 2
    image[:h, :w] = (200, 40, 40)
    image[:h, w:] = (40, 200, 40)
    image[h:, :w] = (40, 40, 200)
    image[h:, w:] = (220, 220, 220)
    return image


def test_segment_finds_the_four_quadrants():
    segmentation = attend.segment(quadrants())
    labels = segmentation["labels"]
    assert labels.shape == (64, 80) and labels.dtype == np.int32
    regions = segmentation["regions"]
    assert sorted(regions["area"].tolist()) == [32 * 40] * 4
    for corner in ((0, 0), (0, 79), (63, 0), (63, 79)):
        region = labels[corner]
        assert np.array_equal(labels == region, labels == labels[corner])
        x, y, w, h = regions["bbox"][region]
        assert (w, h) == (40, 32)
    # Each quadrant borders two others: four boundaries, 32 or 40 pixel edges long.
    assert sorted(segmentation["boundaries"][:, 2].tolist()) == [32, 32, 40, 40]


def test_segment_defaults_to_the_merge_by_spread_of_configs_segment_yaml():
    # A grey texture (128 + uniform noise in [-40, 40]), which the thesis's threshold cuts into
    # dozens of pieces and the merge by spread (configs/segment.yaml) joins.
    rng = np.random.default_rng(7)
    grey = (128 + rng.integers(-40, 41, size=(96, 96))).astype(np.uint8)
    texture = np.repeat(grey[:, :, None], 3, axis=2)
    merged = attend.segment(texture)
    thesis = attend.segment(texture, merge_spread=0, t_max=40)
    assert len(thesis["regions"]["area"]) > 20
    assert len(merged["regions"]["area"]) * 5 < len(thesis["regions"]["area"])
    assert merged["regions"]["area"].max() >= 0.9 * 96 * 96


def test_segment_options_are_the_configuration_keys():
    noisy = quadrants()
    noisy[::2, ::2] //= 2
    fine = attend.segment(noisy, t_max=5, min_region_area=0)
    coarse = attend.segment(noisy, t_max=80)
    assert len(fine["regions"]["area"]) > len(coarse["regions"]["area"])
    with pytest.raises(attend.ConfigError, match="segmentation.t_maxx"):
        attend.segment(noisy, t_maxx=5)
    with pytest.raises(attend.ConfigError, match="segmentation.t_max"):
        attend.segment(noisy, t_max=-1)


def test_disparity_of_a_shifted_texture():
    rng = np.random.default_rng(3)
    texture = rng.integers(0, 256, (120, 200), dtype=np.uint8)
    texture = np.repeat(np.repeat(texture, 2, axis=0), 2, axis=1)[:120, :200]
    left = np.ascontiguousarray(texture[:, 0:160])
    right = np.ascontiguousarray(texture[:, 6:166])  # every point 6 px to the left in right
    disparity = attend.disparity(left, right, max_disparity=16)
    assert disparity.shape == (120, 160) and disparity.dtype == np.float32
    inner = disparity[20:-20, 30:-20]
    assert np.mean(np.abs(inner - 6) <= 1) > 0.95
    with pytest.raises(attend.ConfigError, match="max_disparity"):
        attend.disparity(left, right, max_disparity=0)
    with pytest.raises(attend.InputError, match="right"):
        attend.disparity(left, right[:, :100].copy())


def moving_square(frames=12):
    """A red square moving 3 px a frame to the right over a grey background."""
    for index in range(frames):
        frame = np.full((120, 160, 3), 110, np.uint8)
        x = 20 + 3 * index
        frame[40:70, x:x + 30] = (30, 30, 220)
        yield frame, (x, 40, 30, 30)


def iou(a, b):
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    w = max(0, min(ax + aw, bx + bw) - max(ax, bx))
    h = max(0, min(ay + ah, by + bh) - max(ay, by))
    return w * h / float(aw * ah + bw * bh - w * h)


@pytest.mark.parametrize("kind", ["bip", "kcf", "csrt"])
def test_tracker_follows_a_moving_square(kind):
    tracker = attend.Tracker(kind=kind)
    frames = list(moving_square())
    target = tracker.start(frames[0][0], box=frames[0][1])
    assert target >= 0 and tracker.ids == [target] and tracker.kind == kind
    for frame, truth in frames[1:]:
        (result,) = tracker.track(frame)
        assert result["id"] == target and result["state"] == "found"
        assert iou(result["box"], truth) > 0.6, (result["box"], truth)


def test_tracker_options_are_the_tracker_keys():
    with pytest.raises(attend.ConfigError, match="tracker.kind"):
        attend.Tracker(kind="nope")
    with pytest.raises(attend.ConfigError, match="tracker.not_a_key"):
        attend.Tracker(not_a_key=1)


def test_saliency_of_a_still_image_equals_the_command_line(tmp_path):
    image = quadrants(120, 160)
    image[50:70, 70:90] = (0, 0, 255)
    os.makedirs(tmp_path / "in")
    path = str(tmp_path / "in" / "q.png")
    attend.imwrite(path, image)
    assert np.array_equal(attend.imread(path), image)
    run_attend("saliency", tmp_path / "in", "--out", tmp_path / "maps")
    saliency = attend.saliency(image)
    assert saliency.shape == (120, 160) and saliency.dtype == np.float32
    maps = [name for name in os.listdir(tmp_path / "maps") if name.endswith(".pfm")]
    assert maps, os.listdir(tmp_path / "maps")
    assert np.array_equal(saliency, attend.read_pfm(os.path.join(tmp_path / "maps", maps[0])))
    detailed = attend.saliency(image, features=True)
    assert set(detailed["features"]) >= {"colour_contrast", "intensity_contrast"}
    assert "disparity" in " ".join(detailed["left_out"])


def test_read_run_as_objects_and_dataframes(cli_run):
    run = attend.read_run(cli_run)
    expected = records(os.path.join(cli_run, "frames.jsonl"))
    assert run.frames == expected and len(run.frames) == 12
    assert run.summary["frames"] == 12
    assert "features:" in run.config
    rows = run.target_rows()
    assert len(rows) == sum(len(r["targets"]) for r in expected)
    targets = run.targets_frame()
    assert list(targets.columns[:6]) == ["frame", "id", "x", "y", "w", "h"]
    assert len(targets) == len(rows)
    first = expected[-1]["targets"][0]
    row = targets[(targets.frame == 11) & (targets.id == first["id"])].iloc[0]
    assert [row.x, row.y, row.w, row.h] == first["bbox"]
    frames = run.frames_frame()
    assert len(frames) == 12 and "timing.features" in frames.columns
    assert run.map("saliency", 0).shape == (240, 320)
    with pytest.raises(attend.InputError, match="no such map"):
        run.map("inhibition", 0)


def test_eval_run_equals_attend_eval(cli_run):
    scores = attend.eval_run(cli_run)
    printed = json.loads(run_attend("eval", cli_run).stdout)
    assert scores == printed
    assert 0.0 <= scores["coverage"] <= 1.0


def test_compare_a_run_with_itself(cli_run, tmp_path):
    summary = attend.compare([cli_run, cli_run], out=tmp_path / "cmp")
    assert os.path.isfile(tmp_path / "cmp" / "report.html")
    text = json.dumps(summary)
    assert "cc" in text.lower()


def test_compare_with_ground_truth_given(lab, tmp_path):
    # The lab frames as a plain folder of images: the run has no sequence folder and no gt/.
    out = tmp_path / "images"
    run_attend("run", "--images", os.path.join(lab, "left"), "--out", out, "--quiet",
               "--set", "features=[{name: colour_contrast}]")
    assert attend.compare([out, out])["runs"][0]["attention"] is None
    summary = attend.compare([out, out], gt=os.path.join(lab, "gt"))
    assert summary["runs"][0]["attention"]["objects"] > 0
    assert summary["runs"][1]["ground_truth"].endswith("objects.csv")


def test_errors_are_the_command_lines(tmp_path, lab):
    with pytest.raises(attend.ConfigError) as from_python:
        attend.Pipeline(set=["segmentation.t_maxx=3"])
    printed = run_attend("run", "--sequence", lab, "--out", tmp_path / "r", "--set",
                         "segmentation.t_maxx=3", check=False)
    assert printed.returncode == 2
    assert f"attend: error: {from_python.value}" in printed.stderr
    assert "segmentation.t_maxx" in str(from_python.value)
    config = tmp_path / "bad.yaml"
    config.write_text("segmentation:\n  t_max: 40\n  min_region_area: -4\n")
    with pytest.raises(attend.ConfigError) as from_file:
        attend.Pipeline(config=config)
    assert str(config) in str(from_file.value) and ":3" in str(from_file.value)
    assert "min_region_area" in str(from_file.value)
    with pytest.raises(attend.ConfigError, match="features.0.weight"):
        attend.Pipeline(config={"features": [{"name": "colour_contrast", "weight": "x"}]})
    assert issubclass(attend.ConfigError, attend.Error) and attend.ConfigError.status == 2


def test_bad_frames_are_input_errors():
    pipeline = attend.Pipeline(config={"features": [{"name": "colour_contrast"}]})
    for bad in (np.zeros((8, 8, 4), np.uint8), np.zeros((8, 8, 3), np.float32),
                np.zeros((0, 8, 3), np.uint8), np.zeros(5, np.uint8)):
        with pytest.raises(attend.InputError, match="left"):
            pipeline.process(bad)
    pipeline.process(np.zeros((24, 32, 3), np.uint8))
    with pytest.raises(attend.InputError, match="reset"):
        pipeline.process(np.zeros((30, 32, 3), np.uint8))
    with pytest.raises(attend.InputError, match="right"):
        attend.Pipeline().process(np.zeros((24, 32, 3), np.uint8),
                                  np.zeros((24, 30, 3), np.uint8))
    with pytest.raises(attend.InputError, match="no such|cannot"):
        attend.run("/nonexistent/sequence")
    with pytest.raises(attend.InputError, match="nothing.png"):
        attend.imread("/nonexistent/nothing.png")


def test_eval_fixations_scores_a_perfect_map_above_its_opposite(tmp_path):
    """Two images whose fixations all lie on a square: a map that is 1 there beats its
    opposite, as `attend eval-fixations` scores them."""
    for folder in ("data/stimuli", "data/fixations", "good", "bad"):
        os.makedirs(tmp_path / folder)
    for index, (x, y) in enumerate(((20, 20), (60, 40))):
        image = np.full((80, 100, 3), 128, np.uint8)
        image[y:y + 16, x:x + 16] = (250, 250, 250)
        attend.imwrite(tmp_path / "data" / "stimuli" / f"im{index}.png", image)
        lines = ["# subject x y (1-based)"]
        lines += [f"{s} {x + 4 + 3 * s + 1} {y + 9}" for s in range(3)]
        (tmp_path / "data" / "fixations" / f"im{index}.txt").write_text("\n".join(lines) + "\n")
        good = np.zeros((80, 100), np.float32)
        good[y:y + 16, x:x + 16] = 1
        attend.write_pfm(tmp_path / "good" / f"im{index}.pfm", good)
        attend.write_pfm(tmp_path / "bad" / f"im{index}.pfm", 1 - good)
    assert np.all(attend.read_pfm(tmp_path / "good" / "im1.pfm")[40:56, 60:76] == 1)
    report = attend.eval_fixations({"good": tmp_path / "good", "bad": tmp_path / "bad"},
                                   tmp_path / "data", baselines=["centre"])
    methods = report["methods"]
    assert methods["good"]["auc_judd"]["mean"] == pytest.approx(1.0, abs=0.02)
    assert methods["good"]["nss"]["mean"] > 2.0 > 0.0 > methods["bad"]["nss"]["mean"]
    assert methods["centre"]["images"] == 2
    printed = run_attend("eval-fixations", "good=" + str(tmp_path / "good"),
                         "bad=" + str(tmp_path / "bad"), "--dataset", tmp_path / "data",
                         "--baselines", "centre", "--out", tmp_path / "cli", "--quiet")
    assert printed.returncode == 0
    with open(tmp_path / "cli" / "fixations.json", encoding="utf-8") as file:
        cli = json.load(file)
    assert cli["methods"] == methods


def test_run_reads_a_live_gstreamer_pipeline(tmp_path):
    """attend.run(gst=...) as `attend run --gst`: the records carry their latency, the summary
    the live counts, and the shipped configuration leaves disparity out of a monocular source."""
    import shutil
    import subprocess
    if shutil.which("gst-inspect-1.0") is None:
        pytest.skip("no gst-inspect-1.0 (gstreamer1.0-tools) to tell whether videotestsrc is here")
    if subprocess.run(["gst-inspect-1.0", "videotestsrc"], capture_output=True).returncode != 0:
        pytest.skip("GStreamer's videotestsrc (gstreamer1.0-plugins-base) is not installed")
    pipeline = ("videotestsrc is-live=true num-buffers=8 ! video/x-raw,width=160,height=120,"
                "framerate=30/1 ! videoconvert ! appsink")
    run = attend.run(gst=pipeline, out=tmp_path / "run", set=["live.queue=10"])
    lines = records(tmp_path / "run" / "frames.jsonl")
    assert [line["frame"] for line in lines] == list(range(8))
    assert all(line["latency_ms"] > 0 for line in lines)
    with open(tmp_path / "run" / "summary.json") as handle:
        summary = json.load(handle)
    assert summary["live"]["frames_captured"] == 8
    assert summary["live"]["end"] == "end of stream"
    assert summary["features_left_out"] == ["disparity"]
    with pytest.raises(attend.ConfigError, match="--duration bounds a live source"):
        attend.run(run.dir, duration=1.0)
