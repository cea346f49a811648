"""attend.Pipeline against `attend run`: the same configuration on the same frames gives the
same records and the same maps; maps are handed out without copies; pipelines in threads."""

import os
import re
import threading

import numpy as np
import pytest

import attend
from conftest import ATTEND, records, run_attend, without_timings

TIMINGS = re.compile(r',"timings_ms":\{[^}]*\}')


def cli_map(run, kind, frame):
    return attend.read_pfm(os.path.join(run, kind, f"{frame:06d}.pfm"))


def test_version_is_the_programs():
    printed = run_attend("--version").stdout.strip()
    assert printed == f"attend {attend.__version__}"


def test_records_and_maps_equal_the_command_line(lab_frames, cli_run):
    expected = open(os.path.join(cli_run, "frames.jsonl"), encoding="utf-8").read().splitlines()
    assert len(expected) == len(lab_frames)
    # The rendered lab scene's camera, which `attend synth` writes to its calib.yaml for the
    # command line: the positions in the records agree too.
    pipeline = attend.Pipeline(set=["threads=1"], focal_px=300, baseline_m=0.12)
    attended = set()
    for index, (left, right) in enumerate(lab_frames):
        result = pipeline.process(left, right)
        assert result.frame == index
        # Byte for byte, timings aside.
        assert TIMINGS.sub("", result.record_json) == TIMINGS.sub("", expected[index])
        assert np.array_equal(result.saliency, cli_map(cli_run, "saliency", index))
        assert result.saliency.dtype == np.float32
        assert result.saliency.shape == (240, 320)
        for name, feature_map in result.features.items():
            assert np.array_equal(feature_map, cli_map(cli_run, f"features/{name}", index)), name
        attended.update(t["id"] for t in result.targets)
        for target in result.targets:
            assert set(target) >= {"id", "bbox", "state", "kind", "area", "saliency"}
        assert set(result.timings) >= {"segment", "features", "saliency", "select"}
    # The scene has objects to attend: the comparison is not one of empty records.
    assert len(attended) >= 3


def test_features_by_name_and_normalised(lab_frames):
    pipeline = attend.Pipeline(set=["threads=1"])
    result = pipeline.process(*lab_frames[0])
    assert list(result.features) == ["colour_contrast", "intensity_contrast", "skin",
                                     "disparity"]
    assert list(result.normalised) == list(result.features)
    for normalised in result.normalised.values():
        assert normalised.shape == result.saliency.shape
        assert float(normalised.max()) <= 1.0 + 1e-6


def test_maps_are_the_pipelines_buffers_without_copies(lab_frames):
    pipeline = attend.Pipeline(set=["threads=1"])
    result = pipeline.process(*lab_frames[0])
    buffers = pipeline.buffers()
    assert result.saliency.__array_interface__["data"][0] == buffers["saliency"]
    assert result.inhibition.__array_interface__["data"][0] == buffers["inhibition"]
    for name, feature_map in result.features.items():
        assert feature_map.__array_interface__["data"][0] == buffers[f"features/{name}"]
    # A map that is held keeps its values: the next frame is written into new buffers.
    kept = result.saliency.copy()
    pointer = result.saliency.__array_interface__["data"][0]
    second = pipeline.process(*lab_frames[1])
    assert np.array_equal(result.saliency, kept)
    assert not np.array_equal(second.saliency, kept)
    assert second.saliency.__array_interface__["data"][0] != pointer


def test_reset_starts_the_sequence_again(lab_frames):
    pipeline = attend.Pipeline(set=["threads=1"])
    first = [without_timings(pipeline.process(*f).record) for f in lab_frames[:4]]
    pipeline.reset()
    again = [without_timings(pipeline.process(*f).record) for f in lab_frames[:4]]
    assert first == again


def test_a_dict_configuration_equals_the_file_it_spells(lab_frames, tmp_path):
    path = tmp_path / "two.yaml"
    path.write_text("features:\n  - {name: colour_contrast, weight: 2}\n"
                    "  - {name: intensity_contrast}\n")
    from_file = attend.Pipeline(config=path, set=["threads=1"])
    from_dict = attend.Pipeline(
        config={"features": [{"name": "colour_contrast", "weight": 2},
                             {"name": "intensity_contrast"}]}, set=["threads=1"])
    for frame in lab_frames[:3]:
        a, b = from_file.process(*frame), from_dict.process(*frame)
        assert list(a.features) == ["colour_contrast", "intensity_contrast"]
        assert np.array_equal(a.saliency, b.saliency)
        assert without_timings(a.record) == without_timings(b.record)


def test_monocular_and_grey_frames(lab_frames):
    pipeline = attend.Pipeline(config={"features": [{"name": "colour_contrast"},
                                                    {"name": "intensity_contrast"}]})
    grey = np.ascontiguousarray(lab_frames[0][0][:, :, 1])
    result = pipeline.process(grey)
    assert result.saliency.shape == (240, 320)
    assert pipeline.info["stereo"] is False


def test_two_pipelines_in_two_threads_equal_one_after_the_other(lab_frames):
    def run_all():
        pipeline = attend.Pipeline(set=["threads=1"])
        out = []
        for frame in lab_frames:
            result = pipeline.process(*frame)
            out.append((without_timings(result.record), result.saliency.copy()))
        return out

    sequential = [run_all(), run_all()]
    threaded = [None, None]

    def work(slot):
        threaded[slot] = run_all()

    threads = [threading.Thread(target=work, args=(slot,)) for slot in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for one, other in zip(sequential, threaded):
        assert len(one) == len(other) == len(lab_frames)
        for (record_a, map_a), (record_b, map_b) in zip(one, other):
            assert record_a == record_b
            assert np.array_equal(map_a, map_b)


def test_run_equals_the_command_line(lab, cli_run, tmp_path):
    run = attend.run(lab, out=tmp_path / "run", set=["threads=1",
                                                     "output.dump=[saliency]",
                                                     "output.map_formats=[pfm]"])
    assert run.summary["frames"] == 12
    assert [without_timings(r) for r in run.frames] == \
        [without_timings(r) for r in records(os.path.join(cli_run, "frames.jsonl"))]
    assert np.array_equal(run.map("saliency", 5), cli_map(cli_run, "saliency", 5))


def test_run_refuses_a_used_folder_as_the_command_line_does(lab, cli_run):
    with pytest.raises(attend.OutputError) as error:
        attend.run(lab, out=cli_run)
    assert cli_run in str(error.value)
    assert error.value.status == 2
