"""attend from Python: the attention pipeline of attend on numpy frames (docs/PYTHON.md).

    import attend
    pipeline = attend.Pipeline(config={"features": [{"name": "mcg"}, {"name": "mig"}]})
    result = pipeline.process(left)          # H x W x 3 uint8 BGR, as OpenCV reads it
    result.saliency, result.targets          # float32 map, targets in input pixels

Options are the configuration's keys (configs/README.md, `attend run --list-keys`): a file,
a dict of the same shape, and `set=["key.path=value", ...]` as `attend run --set`. Errors are
attend.ConfigError (a bad key or value, with the key and, for a file, the line), InputError (bad
frames or files), OutputError, PluginError (a Python feature raised), InUseError (a Pipeline or
Tracker called from a second thread while a call runs) and InternalError; all derive from
attend.Error, whose `status` is the exit status `attend` gives for it.
"""

import json as _json
import operator as _operator
import os as _os
import sys as _sys
import tempfile as _tempfile

try:
    import numpy as _numpy  # noqa: F401
except ImportError:
    from ._build import interpreter as _interpreter
    raise ImportError(
        f"attend needs numpy, which this interpreter ({_sys.executable}) does not have; attend "
        f"was built for {_interpreter}, with Debian's python3-numpy: run that interpreter "
        "(or build attend with -DPython_EXECUTABLE=... for this one)") from None

# C++ feature plugins loaded from Python resolve attend's symbols from the module, so it is
# loaded with its symbols global (as the `attend` program exports its own).
_flags = _sys.getdlopenflags()
_sys.setdlopenflags(_flags | _os.RTLD_GLOBAL)
try:
    from . import _attend
finally:
    _sys.setdlopenflags(_flags)

from ._records import Run, read_run  # noqa: E402

__version__ = _attend.__version__

# The most pixels (height x width) of an image or frame handed to attend: OpenCV's limit for
# decoded images, which attend's image readers keep (docs/LIMITS.md); a larger array is an
# InputError before anything is copied.
MAX_IMAGE_PIXELS = _attend.max_image_pixels

Error = _attend.Error
ConfigError = _attend.ConfigError
InputError = _attend.InputError
OutputError = _attend.OutputError
PluginError = _attend.PluginError
InternalError = _attend.InternalError
InUseError = _attend.InUseError
for _error, _status in ((Error, 1), (ConfigError, 2), (OutputError, 2), (InputError, 3),
                        (PluginError, 4), (InternalError, 1), (InUseError, 2)):
    _error.status = _status

__all__ = [
    "Pipeline", "FrameResult", "Tracker", "run", "saliency", "segment", "disparity",
    "read_run", "Run", "read_pfm", "write_pfm", "bundled_sequence", "frames", "imread", "imwrite", "feature", "eval_run", "eval_fixations", "compare", "register_feature",
    "configuration", "keys", "Error", "ConfigError", "InputError", "OutputError",
    "PluginError", "InternalError", "InUseError", "MAX_IMAGE_PIXELS", "__version__",
]


def _overrides(mapping, prefix=""):
    """A dict of configuration keys as `--set` assignments, leaves first-level by first-level."""
    assignments = []
    for key, value in mapping.items():
        path = f"{prefix}{key}"
        if isinstance(value, dict) and value:
            assignments += _overrides(value, path + ".")
        else:
            assignments.append(f"{path}={_json.dumps(value)}")
    return assignments


def _configuration(config=None, set=(), defaults="file"):
    """The options of `config` (a path, a dict, or None) with `set` applied in order.

    None is configs/default.yaml, as for `attend run` (with defaults="file"), or the built-in
    defaults of every key (defaults="keys"). A dict is read as a file of that content would be,
    its keys applied as `--set` assignments over the built-in defaults.
    """
    if isinstance(set, str):
        set = [set]
    if config is None:
        path = _attend.default_config_path() if defaults == "file" else ""
        return _attend.Configuration(path, list(set))
    if isinstance(config, dict):
        return _attend.Configuration("", _overrides(config) + list(set))
    return _attend.Configuration(_os.fspath(config), list(set))


def configuration(config=None, set=()):
    """The effective configuration as YAML text: every key, defaults included."""
    return _configuration(config, set).yaml()


def keys():
    """Every configuration key: dicts of key, type, range, default and doc."""
    return _attend.describe_keys()


class FrameResult:
    """What the pipeline made of one frame.

    saliency, inhibition, inhibited: float32 maps at the working size; features and normalised:
    each feature's raw and normalised map by name; feature_ms: each feature's milliseconds
    (its compute and the shared work it started); record: the frame's frames.jsonl record (a
    dict; boxes and disparities in input pixels), targets its targets (on stereo frames with
    disparity_px and disparity_sd_px; with the Pipeline's camera, position_m and position_sd_m
    too); timings: milliseconds by stage. The maps
    share the pipeline's buffers: no copy is made, and a map you keep keeps its values (the
    pipeline writes the next frame into new buffers while you hold one).
    """

    __slots__ = ("frame", "saliency", "inhibition", "inhibited", "features", "normalised",
                 "feature_ms", "record", "record_json", "targets", "timings", "working_size")

    def __init__(self, raw):
        for key in ("frame", "saliency", "inhibition", "inhibited", "features", "normalised",
                    "feature_ms", "record_json", "timings", "working_size"):
            setattr(self, key, raw[key])
        self.record = _json.loads(self.record_json)
        self.targets = self.record["targets"]

    def __repr__(self):
        return (f"<attend.FrameResult frame {self.frame}: {len(self.targets)} targets, "
                f"working size {self.working_size[0]}x{self.working_size[1]}>")


class Pipeline:
    """The attention loop of `attend run` over frames you hand it one at a time.

    config: a configuration file, a dict of configuration keys, or None for
    configs/default.yaml; set: "key.path=value" overrides. The GIL is released while a frame is
    processed, so pipelines in several threads run at once; one pipeline runs one call at a time,
    and a call from another thread meanwhile (process, reset, info, buffers) raises
    attend.InUseError.

    focal_px and baseline_m (with principal_point, (cx, cy), default the image centre; all in
    the pixels of the frames handed in) describe a rectified stereo camera: each target seen in
    a stereo frame then has "position_m" [X, Y, Z] (metres, left camera's frame: X right, Y
    down, Z forward) and "position_sd_m" besides its "disparity_px" (SPEC 3.3), as `attend run`
    gives them with sequence.yaml's focal_px and baseline_m.
    """

    def __init__(self, config=None, set=(), *, focal_px=None, baseline_m=None,
                 principal_point=None):
        if (focal_px is None) != (baseline_m is None):
            raise ConfigError("focal_px and baseline_m: give both (a stereo camera) or neither")
        if principal_point is not None and focal_px is None:
            raise ConfigError("principal_point: needs focal_px and baseline_m")
        camera = {}
        if focal_px is not None:
            camera = {"focal_px": float(focal_px), "baseline_m": float(baseline_m)}
        if principal_point is not None:
            cx, cy = principal_point
            camera.update(cx=float(cx), cy=float(cy))
        self._options = _configuration(config, set)
        self._core = _attend.Pipeline(self._options, **camera)

    def process(self, left, right=None, index=None):
        """Runs one frame (left and optional right: H x W x 3 uint8 BGR or H x W grey);
        index, when given, is its frame number, 0..1000000 as in frames.jsonl."""
        if index is None:
            index = -1
        else:
            index = _operator.index(index)
            if not 0 <= index <= _attend.max_frame_number:
                raise InputError(f"index: {index} is not a frame number "
                                 f"(0..{_attend.max_frame_number}, docs/LIMITS.md)")
        return FrameResult(self._core.process(left, right, index))

    def reset(self):
        """Ends the sequence; the next frame starts a new one (new targets, new memory)."""
        self._core.reset()

    @property
    def config(self):
        """The effective configuration as YAML text."""
        return self._options.yaml()

    def buffers(self):
        """Addresses of the C++ buffers of the last frame's maps (by "saliency",
        "features/NAME", ...): a map array's data pointer is its buffer's."""
        return self._core.buffers()

    @property
    def info(self):
        """started, stereo, input_size, working_size, and calibration (focal_px, baseline_m,
        principal_point; None without a camera or on monocular frames)."""
        return self._core.info()


class Tracker:
    """A tracker of `kind` (bip, kcf, csrt) on numpy frames, as `attend track`; options are the
    configuration's tracker keys (e.g. mode="thesis", lost_frames=5). The BIP starts from
    configs/track.yaml (the correlation mode, docs/TRACKING.md): mode="thesis" gives the
    thesis's tracker, mode="bounded", occlusion=True the bounded mode with its occlusion rules.
    One call at a time: a call from another thread while one runs raises attend.InUseError."""

    def __init__(self, kind="bip", **options):
        overrides = _overrides({"tracker": dict(options, kind=kind)})
        path = _attend.track_config_path(kind)
        self._core = _attend.Tracker(_attend.Configuration(path, overrides))

    def start(self, frame, box=None, mask=None):
        """Starts a target from a box [x, y, w, h] or a mask; returns its id (-1: no target)."""
        if (box is None) == (mask is None):
            raise ConfigError("start: give either box or mask")
        if box is not None:
            return self._core.start(frame, [int(v) for v in box])
        return self._core.start_mask(frame, mask)

    def track(self, frame):
        """Searches every target; one dict a target: id, state, box, area, roi."""
        return self._core.track(frame)

    def mask(self, target_id):
        return self._core.mask(target_id)

    def remove(self, target_id):
        self._core.remove(target_id)

    @property
    def ids(self):
        return self._core.ids

    @property
    def kind(self):
        return self._core.kind


def run(sequence=None, *, config=None, set=(), video=None, left_video=None, right_video=None,
        side_by_side_video=None, images=None, camera=None, camera_right=None, gst=None,
        gst_right=None, side_by_side_live=False, duration=None, frames="", out="",
        overwrite=False, calib=None):
    """`attend run`: the pipeline over a source into a run folder; returns the folder's Run.

    The sources are those of `attend run` (a sequence folder, videos, an image folder, a live
    V4L2 camera or GStreamer pipeline and its right twin, docs/LIVE.md); none runs the
    configuration's own source. `duration` (seconds) bounds a live run as --duration does;
    `calib` is a stereo calibration file as --calib (docs/STEREO3D.md).
    With no `config`, a monocular source leaves the stereo features out, as the command does.
    KeyboardInterrupt stops it after the current frame, with the run folder closed as
    interrupted, and is raised again.
    """
    if isinstance(set, str):
        set = [set]
    if isinstance(config, dict):
        handle = _tempfile.NamedTemporaryFile("w", suffix=".yaml", prefix="attend-config-",
                                              delete=False)
        with handle:
            handle.write(_configuration(config).yaml())
        config_path = handle.name
    else:
        config_path = "" if config is None else _os.fspath(config)
    source = {"sequence": sequence, "video": video, "left_video": left_video,
              "right_video": right_video, "side_by_side_video": side_by_side_video,
              "images": images, "calib": calib}
    source = {k: _os.fspath(v) for k, v in source.items() if v is not None}
    live = {"camera": camera, "camera_right": camera_right, "gst": gst, "gst_right": gst_right}
    # An empty path is never meant (an unset variable): it would run the configuration's own
    # source instead, as `attend run --video ''` used to.
    for key, value in list(source.items()) + [("gst", gst), ("gst_right", gst_right),
                                               ("config", config), ("out", out or None)]:
        if isinstance(value, (str, bytes, _os.PathLike)) and _os.fspath(value) in ("", b""):
            raise ConfigError(f"attend.run: {key} is an empty path or value (an unset "
                              "variable?); leave it out instead")
    source.update({k: v for k, v in live.items() if v is not None})
    source["side_by_side_live"] = bool(side_by_side_live)
    try:
        summary = _attend.run(config_path, list(set), source, frames, _os.fspath(out), overwrite,
                              -1.0 if duration is None else float(duration))
    finally:
        if isinstance(config, dict):
            _os.unlink(config_path)
    return read_run(summary["dir"])


def bundled_sequence(quiet=True):
    """The folder of the bundled lab sequence (sequences/lab.yaml), rendered on first use as
    `attend run` does: a stereo sequence with ground truth."""
    return _attend.bundled_sequence(quiet)


def frames(sequence):
    """The frames of a sequence folder (SEQ/left and SEQ/right, or SEQ/left alone) or of a
    plain folder of images, in frame order and read as `attend run` reads them, as (left, right)
    BGR arrays (right None when monocular)."""
    sequence = _os.fspath(sequence)
    left = _os.path.join(sequence, "left")
    if not _os.path.isdir(left):
        left, right = sequence, None
    else:
        right = _os.path.join(sequence, "right")
        right = right if _os.path.isdir(right) else None
    lefts = _attend._frame_files(left)
    if not lefts:
        raise InputError(f"{left}: no frames (.png, .jpg, .jpeg, .ppm, .pgm)")
    rights = None if right is None else _attend._frame_files(right)
    if rights is not None and [_os.path.basename(p) for p in rights] != \
            [_os.path.basename(p) for p in lefts]:
        raise InputError(f"{right}: its frame names differ from those of {left}")
    for index, path in enumerate(lefts):
        yield (_attend._frame_file(index, path),
               None if rights is None else _attend._frame_file(index, rights[index]))


def _existing_file(path):
    """path, after an InputError if it names something that is not a regular file: a folder,
    or a fifo or device that would be read for ever (read_pfm("/dev/zero") hung)."""
    path = _os.fspath(path)
    if _os.path.exists(path) and not _os.path.isfile(path):
        _attend._check_regular_file(path)
    return path


def imread(path, grey=False):
    """An image file as OpenCV's imread gives it: H x W x 3 uint8 BGR (H x W with grey); a file
    cut short is an InputError, not a part-grey image."""
    return _attend.imread(_existing_file(path), grey)


def imwrite(path, image):
    """Writes an 8-bit BGR or grey array to an image file (the extension says the format),
    making the folders above it."""
    _attend.imwrite(_os.fspath(path), image)


def read_pfm(path):
    """A PFM file (the run's lossless maps) as a float32 array, top row first."""
    return _attend.read_pfm(_existing_file(path))


def write_pfm(path, image):
    """Writes a float map (H x W, or H x W x 3) as PFM, the format of the run's lossless maps
    and of the saliency folders that eval_fixations scores."""
    _attend.write_pfm(_os.fspath(path), image)


def saliency(image, config=None, set=(), features=False):
    """The pre-attentive stage on one still image (`attend saliency`): the saliency map at the
    image's size, float32 in [0, 1]; with features=True a dict with the features' maps too."""
    result = _attend.saliency(image, _configuration(config, set), features)
    return result if features else result["saliency"]


def segment(image, **options):
    """BIP colour segmentation of an image (`attend segment`); options are the configuration's
    segmentation keys (t_max, min_region_area, merge_spread, ...), each replacing the value of
    configs/segment.yaml, as `--set` does for the command. Returns labels, regions,
    boundaries."""
    overrides = _overrides({"segmentation": options}) if options else []
    return _attend.segment(image, _attend.Configuration(_attend.segment_config_path(), overrides))


def disparity(left, right, **options):
    """The disparity map of a rectified pair (`attend disparity`), float32 pixels; options are
    the disparity feature's keys (max_disparity, window, smoothness, ...)."""
    return _attend.disparity(left, right, _overrides({"disparity": options}))


def eval_run(run_dir, gt=""):
    """`attend eval`: the run's scores against its sequence's ground truth (or gt) as a dict."""
    return _json.loads(_attend.eval_run(_os.fspath(run_dir), _os.fspath(gt)))


def eval_fixations(maps, dataset, *, out=None, baselines=(), sigma=0.0, max_side=640, skip=0,
                   first=0):
    """`attend eval-fixations`: saliency folders ("NAME=FOLDER" or a {name: folder} dict)
    scored against a fixation dataset; returns fixations.json's content as a dict."""
    if isinstance(maps, dict):
        maps = [f"{name}={_os.fspath(folder)}" for name, folder in maps.items()]
    elif isinstance(maps, (str, _os.PathLike)):
        maps = [_os.fspath(maps)]
    with _tempfile.TemporaryDirectory(prefix="attend-fixations-") as scratch:
        folder = _os.fspath(out) if out else scratch
        result = _attend.eval_fixations([_os.fspath(m) for m in maps], _os.fspath(dataset),
                                        folder, list(baselines), sigma, max_side, skip, first)
        with open(_os.path.join(folder, "fixations.json"), encoding="utf-8") as file:
            report = _json.load(file)
    report["table"] = result["table"]
    return report


def compare(runs, out=None, overwrite=False, gt=None):
    """`attend compare`: each run against the first; returns summary.json's content as a dict
    (the report.html beside it when out is given). gt: a gt/ folder (holding objects.csv) for
    every run, or a list of one a run, for runs whose source has none (`--gt`)."""
    runs = [_os.fspath(r) for r in runs]
    if gt is None:
        gt = []
    elif isinstance(gt, (str, _os.PathLike)):
        gt = [_os.fspath(gt)]
    else:
        gt = [_os.fspath(g) for g in gt]
    with _tempfile.TemporaryDirectory(prefix="attend-compare-") as scratch:
        folder = _os.fspath(out) if out else _os.path.join(scratch, "report")
        _attend.compare(runs, folder, overwrite, gt)
        with open(_os.path.join(folder, "summary.json"), encoding="utf-8") as file:
            return _json.load(file)


def register_feature(name, cls):
    """Registers a Python feature class under `name`, usable in any configuration's features.

    The class has compute(self, context) returning a map of the context's size (anything numpy
    turns into float32 H x W); optional: an `options` dict of defaults (read from the feature's
    entry, each with its default's type, and passed to the constructor as keywords),
    `needs_stereo = True`, begin_sequence(self, info) and end_sequence(self). Registering a name
    again replaces the class. Returns cls, so it can be used as a decorator factory's result.
    """
    _attend._register_feature(name, cls)
    return cls


def feature(name):
    """Decorator form of register_feature: @attend.feature("my_feature")."""
    def decorate(cls):
        return register_feature(name, cls)
    return decorate
