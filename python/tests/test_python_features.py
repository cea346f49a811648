"""Feature plugins written in Python: registered from Python or named as a .py file in
`plugins:`, computed on the frame context's arrays, with their options from the YAML entry."""

import json
import os
import textwrap

import numpy as np
import pytest

import attend
from conftest import ATTEND, run_attend, without_timings

TWO = [{"name": "intensity_contrast"}]


class BuiltinColourContrast:
    """The C++ colour contrast's map, handed back from Python."""

    def compute(self, context):
        return context.builtin("colour_contrast")


class NumpyColourContrast:
    """MCG (thesis eq. 5.1, SPEC 2.3) from the context's regions, in numpy."""

    def compute(self, context):
        segmentation = context.regions
        regions = segmentation["regions"]
        colour = regions["colour"].astype(np.float64)
        boundaries = segmentation["boundaries"]
        a, b, length = boundaries[:, 0], boundaries[:, 1], boundaries[:, 2].astype(np.float64)
        distance = np.linalg.norm(colour[a] - colour[b], axis=1) * length
        sums = np.bincount(a, distance, len(colour)) + np.bincount(b, distance, len(colour))
        perimeter = regions["perimeter"].astype(np.float64)
        values = np.where(perimeter > 0, sums / np.maximum(perimeter, 1), 0.0)
        values *= regions["saturation"] / 255.0
        return values[segmentation["labels"]]


def test_a_python_feature_returning_the_cpp_map_gives_the_same_saliency(lab_frames):
    attend.register_feature("py_colour_contrast", BuiltinColourContrast)
    cpp = attend.Pipeline(config={"features": [{"name": "colour_contrast"}] + TWO},
                          set=["threads=1"])
    py = attend.Pipeline(config={"features": [{"name": "py_colour_contrast"}] + TWO},
                         set=["threads=1"])
    for frame in lab_frames:
        a, b = cpp.process(*frame), py.process(*frame)
        assert np.array_equal(a.features["colour_contrast"], b.features["py_colour_contrast"])
        assert np.array_equal(a.saliency, b.saliency)
        assert without_timings(a.record) == without_timings(b.record)


def test_a_numpy_colour_contrast_from_the_regions_matches_the_cpp_one(lab_frames):
    attend.register_feature("numpy_mcg", NumpyColourContrast)
    pipeline = attend.Pipeline(config={"features": [{"name": "colour_contrast"},
                                                    {"name": "numpy_mcg"}]},
                               set=["threads=1"])
    for frame in lab_frames[:4]:
        result = pipeline.process(*frame)
        cpp, py = result.features["colour_contrast"], result.features["numpy_mcg"]
        assert float(cpp.max()) > 1.0
        np.testing.assert_allclose(py, cpp, rtol=1e-4, atol=1e-3)


def test_the_context_gives_the_frame_planes_and_disparity(lab_frames):
    seen = {}

    class Probe:
        needs_stereo = True

        def compute(self, context):
            seen["left"] = np.array(context.left)
            seen["cylinder"] = context.cylinder.shape
            seen["tsl"] = context.tsl.shape
            seen["disparity"] = np.array(context.disparity)
            seen["size"] = context.size
            seen["stereo"] = context.stereo
            seen["index"] = context.frame_index
            seen["writeable"] = context.left.flags.writeable
            return np.zeros(context.left.shape[:2], np.uint8)

    attend.register_feature("probe", Probe)
    pipeline = attend.Pipeline(config={"features": [{"name": "probe"}]}, set=["threads=1"])
    left, right = lab_frames[3]
    pipeline.process(left, right, index=3)
    assert np.array_equal(seen["left"], left)  # the working size is the lab's own 320x240
    assert seen["cylinder"] == (240, 320, 3) and seen["tsl"] == (240, 320, 3)
    assert seen["size"] == (320, 240) and seen["stereo"] is True and seen["index"] == 3
    assert seen["writeable"] is False
    disparity = seen["disparity"]
    assert disparity.shape == (240, 320) and disparity.dtype == np.float32
    # Equal to attend.disparity with the feature's defaults on the same pair.
    assert np.array_equal(disparity, attend.disparity(left, right))


class Gain:
    """A constant map whose level is an option."""

    options = {"level": 1.0, "mode": "flat"}

    def __init__(self, level, mode):
        self.level, self.mode = level, mode

    def compute(self, context):
        height, width = context.left.shape[:2]
        return np.full((height, width), self.level, np.float64)


def test_options_come_from_the_feature_entry():
    attend.register_feature("gain", Gain)
    pipeline = attend.Pipeline(config={"features": [{"name": "gain", "level": 2.5}]})
    frame = np.full((48, 64, 3), 90, np.uint8)
    result = pipeline.process(frame)
    assert float(result.features["gain"].max()) == 2.5
    with pytest.raises(attend.ConfigError, match=r"levle.*features\.0"):
        attend.Pipeline(config={"features": [{"name": "gain", "levle": 2.5}]})
    with pytest.raises(attend.ConfigError, match=r"features\.0\.level"):
        attend.Pipeline(config={"features": [{"name": "gain", "level": "high"}]})


def test_a_raising_feature_is_a_plugin_error_with_its_traceback():
    class Broken:
        def compute(self, context):
            return 1 / 0

    attend.register_feature("broken", Broken)
    pipeline = attend.Pipeline(config={"features": [{"name": "broken"}]})
    with pytest.raises(attend.PluginError) as error:
        pipeline.process(np.zeros((32, 32, 3), np.uint8))
    text = str(error.value)
    assert "feature 'broken'" in text
    assert "Traceback" in text and "ZeroDivisionError" in text and "return 1 / 0" in text
    assert error.value.status == 4


def test_a_map_of_the_wrong_shape_or_kind_is_a_plugin_error():
    class WrongShape:
        def compute(self, context):
            return np.zeros((3, 3), np.float32)

    class NotNumbers:
        def compute(self, context):
            return "map"

    attend.register_feature("wrong_shape", WrongShape)
    attend.register_feature("not_numbers", NotNumbers)
    frame = np.zeros((240, 320, 3), np.uint8)
    with pytest.raises(attend.PluginError, match=r"\(3, 3\).*\(240, 320\)"):
        attend.Pipeline(config={"features": [{"name": "wrong_shape"}]}).process(frame)
    with pytest.raises(attend.PluginError, match="not an array of numbers"):
        attend.Pipeline(config={"features": [{"name": "not_numbers"}]}).process(frame)


def test_a_context_kept_after_compute_refuses_use():
    kept = []

    class Keeper:
        def compute(self, context):
            kept.append(context)
            return np.zeros(context.left.shape[:2], np.float32)

    attend.register_feature("keeper", Keeper)
    attend.Pipeline(config={"features": [{"name": "keeper"}]}).process(
        np.zeros((16, 16, 3), np.uint8))
    with pytest.raises(attend.PluginError, match="after its compute"):
        kept[0].left


def test_register_feature_refuses_bad_names_and_classes():
    with pytest.raises(attend.ConfigError, match="built-in"):
        attend.register_feature("colour_contrast", Gain)
    with pytest.raises(attend.ConfigError, match="not a feature name"):
        attend.register_feature("two words", Gain)
    with pytest.raises(attend.ConfigError, match="compute"):
        attend.register_feature("nothing", object)


PLUGIN = textwrap.dedent('''
    """A red-channel feature, named in plugins: as a file."""
    import numpy as np
    import attend

    class Red:
        options = {"scale": 1.0}

        def __init__(self, scale):
            self.scale = scale

        def compute(self, context):
            return context.left[:, :, 2].astype(np.float32) * self.scale

    attend.register_feature("red", Red)
''')


def write(folder, name, text):
    path = folder / name
    path.write_text(text)
    return path


def test_the_command_line_runs_a_python_plugin(lab, tmp_path, lab_frames):
    plugin = write(tmp_path, "red.py", PLUGIN)
    out = tmp_path / "run"
    run_attend("run", "--sequence", lab, "--out", out, "--quiet", "--frames", "0:2",
               "--set", f"plugins=[{plugin}]",
               "--set", "features=[{name: colour_contrast}, {name: red, scale: 0.5}]",
               "--set", "output.dump=[features]", "--set", "output.map_formats=[pfm]")
    red = attend.read_pfm(os.path.join(out, "features", "red", "000001.pfm"))
    expected = lab_frames[1][0][:, :, 2].astype(np.float32) * 0.5
    assert np.array_equal(red, expected)
    # The same file loaded by a Python pipeline gives the same map.
    pipeline = attend.Pipeline(config={"plugins": [str(plugin)],
                                       "features": [{"name": "red", "scale": 0.5}]})
    assert np.array_equal(pipeline.process(*lab_frames[1]).features["red"], expected)


def test_a_raising_plugin_exits_4_with_the_traceback(lab, tmp_path):
    plugin = write(tmp_path, "bad.py", PLUGIN.replace(
        "return context.left", "raise ValueError('no red here')\n        return context.left"))
    result = run_attend("run", "--sequence", lab, "--out", tmp_path / "run", "--quiet",
                        "--frames", "0:2", "--set", f"plugins=[{plugin}]",
                        "--set", "features=[{name: red}]", check=False)
    assert result.returncode == 4, result.stderr
    assert "attend: error:" in result.stderr
    assert "feature 'red'" in result.stderr
    assert "Traceback" in result.stderr and "ValueError: no red here" in result.stderr
    assert f'File "{plugin}"' in result.stderr
    # The frames done before the error are kept, as for any error in a run.
    assert os.path.isfile(tmp_path / "run" / "summary.json")


def test_a_plugin_file_that_fails_or_registers_nothing(lab, tmp_path):
    broken = write(tmp_path, "syntax.py", "def broken(:\n")
    empty = write(tmp_path, "empty.py", "x = 1\n")
    result = run_attend("run", "--sequence", lab, "--out", tmp_path / "a", "--quiet",
                        "--set", f"plugins=[{broken}]", check=False)
    assert result.returncode == 4 and "SyntaxError" in result.stderr
    assert "plugins.0" in result.stderr and str(broken) in result.stderr
    result = run_attend("run", "--sequence", lab, "--out", tmp_path / "b", "--quiet",
                        "--set", f"plugins=[{empty}]", check=False)
    assert result.returncode == 2 and "registered no feature" in result.stderr
    result = run_attend("run", "--sequence", lab, "--out", tmp_path / "c", "--quiet",
                        "--set", f"plugins=[{tmp_path / 'missing.py'}]", check=False)
    assert result.returncode == 2 and "no such file" in result.stderr
    # None of them left a run folder behind.
    assert not any((tmp_path / name).exists() for name in "abc")


def test_the_program_does_not_link_python():
    import subprocess
    libraries = subprocess.run(["ldd", ATTEND], capture_output=True, text=True).stdout
    assert "libpython" not in libraries


def test_a_feature_that_runs_ahead_gives_the_records_of_one_thread(lab, tmp_path):
    """With two threads `attend run` computes frame t + 1's features on a second thread while
    it finishes frame t: a Python feature that says it never reads attention_regions runs
    there (holding the interpreter only while it computes), one that does not say so waits,
    and both give the records of one thread."""
    ahead = write(tmp_path, "ahead.py", PLUGIN.replace(
        'options = {"scale": 1.0}', 'options = {"scale": 1.0}\n    reads_attention_regions = False'))
    waits = write(tmp_path, "waits.py", PLUGIN.replace('"red"', '"red_late"'))
    records = {}
    for name, threads in (("one", 1), ("two", 2)):
        out = tmp_path / name
        run_attend("run", "--sequence", lab, "--out", out, "--quiet", "--frames", "0:8",
                   "--set", f"plugins=[{ahead}, {waits}]",
                   "--set", "features=[{name: colour_contrast}, {name: red, scale: 0.5}, "
                            "{name: red_late, scale: 0.25}]",
                   "--set", f"threads={threads}")
        with open(out / "frames.jsonl") as lines:
            records[name] = [without_timings(json.loads(line)) for line in lines]
    assert len(records["one"]) == 9
    assert records["two"] == records["one"]
