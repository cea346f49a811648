"""Bad input to the module, round 3 (issue 46): frames too large to take, refused at once before
any copy (case 2), and a Python feature's map that is not finite, the feature's fault
(PluginError, exit 4 on the command line; case 3)."""

import os
import textwrap
import time

import numpy as np
import pytest

import attend
from conftest import run_attend

CAP = attend.MAX_IMAGE_PIXELS


def huge(height, width, channels=3):
    """A uint8 array of that shape that allocates one pixel: a broadcast (strided) view, which
    a copy into a contiguous buffer would make H x W x C bytes."""
    shape = (height, width) if channels == 1 else (height, width, channels)
    return np.broadcast_to(np.zeros((1,) * len(shape), np.uint8), shape)


def test_the_cap_is_opencvs_decoder_limit():
    # The same number as the image readers' (io/png_fast.h kMaxDecodedPixels), bound from C++.
    assert CAP == 2 ** 30


@pytest.mark.parametrize("call, what", [
    (lambda image: attend.Pipeline(config={"features": [{"name": "colour_contrast"}]})
     .process(image), "left"),
    (lambda image: attend.Pipeline(config={"features": [{"name": "colour_contrast"}]})
     .process(np.zeros((8, 8, 3), np.uint8), image), "right"),
    (lambda image: attend.saliency(image), "image"),
    (lambda image: attend.segment(image), "image"),
    (lambda image: attend.disparity(image, image), "left"),
    (lambda image: attend.Tracker().start(image, box=(0, 0, 8, 8)), "frame"),
    (lambda image: attend.Tracker().track(image), "frame"),
    (lambda image: attend.imwrite("/nonexistent/never.png", image), "image"),
])
def test_a_frame_over_the_cap_is_an_input_error_at_once(call, what):
    started = time.monotonic()
    with pytest.raises(attend.InputError) as error:
        call(huge(40000, 40000))
    assert time.monotonic() - started < 2.0  # it took 7 s and 4.8 GB to fail before
    message = str(error.value)
    assert message.startswith(f"{what}: an image of 40000 x 40000 pixels (1600000000 in all)")
    assert f"at most {CAP} pixels (attend.MAX_IMAGE_PIXELS" in message
    assert error.value.status == 3


@pytest.mark.parametrize("shape", [(1, CAP + 1, 3), (CAP + 1, 1, 1), (2 ** 15, 2 ** 15 + 1, 3)])
def test_any_shape_one_pixel_over_the_cap_is_refused(shape):
    height, width, channels = shape
    with pytest.raises(attend.InputError, match=f"{width} x {height} pixels"):
        attend.saliency(huge(height, width, channels))


def test_a_mask_over_the_cap_is_refused_before_its_copy():
    with pytest.raises(attend.InputError, match="^mask: an image of 40000 x 40000"):
        attend.Tracker().start(np.zeros((8, 8, 3), np.uint8), mask=huge(40000, 40000, 1))


def test_strided_views_under_the_cap_are_taken_as_their_copies(tmp_path):
    rng = np.random.default_rng(46)
    wide = rng.integers(0, 256, (60, 160, 3), np.uint8)
    left, right = wide[:, ::2], wide[:, 1::2]  # not contiguous: each is copied
    assert not left.flags.c_contiguous
    assert np.array_equal(attend.disparity(left, right, max_disparity=8),
                          attend.disparity(np.ascontiguousarray(left),
                                           np.ascontiguousarray(right), max_disparity=8))
    attend.imwrite(tmp_path / "view.png", left)
    assert np.array_equal(attend.imread(tmp_path / "view.png"), left)


class NotFinite:
    """A map of zeros with one value not finite at (x 7, y 3), from frame 1 on."""

    options = {"value": "nan"}

    def __init__(self, value):
        self.value = float(value)

    def compute(self, context):
        map = np.zeros(context.left.shape[:2], np.float32)
        if context.frame_index >= 1:
            map[3, 7] = self.value
            map[5:, :] = self.value
        return map


@pytest.mark.parametrize("value, shown", [("nan", "NaN"), ("inf", "inf"), ("-inf", "-inf")])
def test_a_python_feature_map_not_finite_is_a_plugin_error(value, shown):
    attend.register_feature("not_finite", NotFinite)
    pipeline = attend.Pipeline(config={"features": [{"name": "not_finite", "value": value}]})
    frame = np.zeros((24, 32, 3), np.uint8)
    pipeline.process(frame)  # frame 0: finite
    with pytest.raises(attend.PluginError) as error:
        pipeline.process(frame)
    message = str(error.value)
    # The working size of a 32 x 24 frame is 320 x 240: (x 7, y 3) stays the first bad pixel.
    assert message.startswith(f"feature 'not_finite' (Python): compute(): returned a map with "
                              f"{shown} at pixel (x 7, y 3) of frame 1 (")
    assert "a feature map must be finite everywhere" in message
    assert error.value.status == 4


# The same feature as a plugin file of the `attend` program.
PLUGIN = '''
import numpy as np
import attend

class NotFinite:
    def compute(self, context):
        map = np.zeros(context.left.shape[:2], np.float32)
        if context.frame_index == 1:
            map[10, 20] = np.nan
        return map

attend.register_feature("not_finite", NotFinite)
'''


def test_the_command_line_exits_4_on_a_python_feature_map_not_finite(lab, tmp_path):
    plugin = tmp_path / "not_finite.py"
    plugin.write_text(textwrap.dedent(PLUGIN))
    result = run_attend("run", "--sequence", lab, "--out", tmp_path / "run", "--quiet",
                        "--frames", "0:2", "--set", f"plugins=[{plugin}]",
                        "--set", "features=[{name: colour_contrast}, {name: not_finite}]",
                        check=False)
    assert result.returncode == 4, result.stderr
    assert ("attend: error: feature 'not_finite' (Python): compute(): returned a map with NaN "
            "at pixel (x 20, y 10) of frame 1") in result.stderr
    # Frame 0 was done before the error, and is kept.
    assert os.path.isfile(tmp_path / "run" / "frames.jsonl")


def test_a_pfm_map_over_the_cap_is_refused_before_its_copy(tmp_path):
    # It wrote 3.6 GB in 20 s before: the conversion to float32 copied the view first.
    started = time.monotonic()
    path = tmp_path / "huge.pfm"
    flat = np.broadcast_to(np.float32(0), (40000, 40000))
    with pytest.raises(attend.InputError, match="a map of 40000 x 40000 pixels is more than"):
        attend.write_pfm(path, flat)
    assert time.monotonic() - started < 2.0 and not path.exists()


@pytest.mark.parametrize("read", [attend.read_pfm, attend.imread])
def test_reading_a_device_or_folder_as_an_image_is_refused_at_once(read, tmp_path):
    # read_pfm("/dev/zero") read for ever.
    with pytest.raises(attend.InputError, match=r"^/dev/zero: is not a regular file \("):
        read("/dev/zero")
    with pytest.raises(attend.InputError, match=f"^{tmp_path}: is a folder, not a file"):
        read(tmp_path)
    with pytest.raises(attend.InputError, match="no such|cannot open|does not exist"):
        read(tmp_path / "missing.pfm")


def test_a_frame_index_out_of_the_records_range_is_refused():
    pipeline = attend.Pipeline(config={"features": [{"name": "colour_contrast"}]})
    frame = np.zeros((24, 32, 3), np.uint8)
    for index in (-5, 1000001, 2 ** 31, 2 ** 70):
        with pytest.raises(attend.InputError, match=f"^index: {index} is not a frame number "
                                                    r"\(0\.\.1000000"):
            pipeline.process(frame, index=index)
    with pytest.raises(attend.InputError, match="^index: -2 is not a frame number"):
        pipeline._core.process(frame, None, -2)  # the C++ check under the Python one
    assert pipeline.process(frame, index=1000000).frame == 1000000


@pytest.mark.parametrize("key", ["video", "images", "left_video", "gst", "sequence", "config"])
def test_an_empty_source_path_is_refused_not_replaced_by_the_bundled_sequence(key, tmp_path):
    kwargs = {key: "", "out": tmp_path / "run"}
    if key == "left_video":
        kwargs["right_video"] = "right.avi"
    args = ("",) if key == "sequence" else ()
    if key == "sequence":
        del kwargs["sequence"]
    with pytest.raises(attend.ConfigError, match=f"attend.run: {key} is an empty path"):
        attend.run(*args, **kwargs)
    assert not (tmp_path / "run").exists()
