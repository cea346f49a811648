"""Reading a run folder (SPEC 3.3) into Python objects and, with pandas, DataFrames."""

import json
import os

from . import _attend


# The columns a target's depth gives a row (issue 44, SPEC 3.3): its disparity and standard
# deviation (input pixels), and with a calibration its position in the left camera's frame
# (metres; X right, Y down, Z forward) and each coordinate's standard deviation.
DEPTH_COLUMNS = ("disparity_px", "disparity_sd_px", "x_m", "y_m", "z_m", "x_sd_m", "y_sd_m",
                 "z_sd_m")
TARGET_COLUMNS = ["frame", "id", "x", "y", "w", "h", "area", "saliency", "state", "kind"]


def target_depth(target):
    """A target dict's depth (a frames.jsonl target) as the values of DEPTH_COLUMNS, None for
    each that the record does not have."""
    position = target.get("position_m") or (None, None, None)
    sd = target.get("position_sd_m") or (None, None, None)
    return {"disparity_px": target.get("disparity_px"),
            "disparity_sd_px": target.get("disparity_sd_px"),
            "x_m": position[0], "y_m": position[1], "z_m": position[2],
            "x_sd_m": sd[0], "y_sd_m": sd[1], "z_sd_m": sd[2]}


def _input_error(message):
    return _attend.InputError(message)


_JSON_NAMES = {dict: "an object", list: "a list", str: "a string", int: "a number",
               float: "a number", bool: "true or false", type(None): "null"}


def _text(path):
    """A file of the run folder as UTF-8 text; InputError naming it otherwise."""
    try:
        with open(path, "rb") as file:
            data = file.read()
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise _input_error(f"{path}: not UTF-8 text (byte {error.start + 1}: "
                           f"{data[error.start:error.start + 1]!r})") from None
    except OSError as error:
        raise _input_error(f"{path}: cannot read ({error.strerror})") from None


def _lines(path):
    """(number, text) of the file's lines, split at \\n alone as the C++ reader splits them."""
    try:
        with open(path, "rb") as file:
            data = file.read()
    except OSError as error:
        raise _input_error(f"{path}: cannot read ({error.strerror})") from None
    for number, raw in enumerate(data.split(b"\n"), 1):
        try:
            yield number, raw.decode("utf-8")
        except UnicodeDecodeError as error:
            raise _input_error(f"{path}:{number}: not UTF-8 text (byte {error.start + 1} of "
                               "the line)") from None


def _refuse_constant(name):
    raise ValueError(f"{name} is not JSON")


def _parse(text, where, what, kind):
    """JSON text as the C++ readers take it (no NaN or Infinity) of the type `kind`;
    InputError at `where` otherwise."""
    try:
        value = json.loads(text, parse_constant=_refuse_constant)
    except (ValueError, RecursionError) as error:
        raise _input_error(f"{where}: {what} ({type(error).__name__}: {error})") from None
    if not isinstance(value, kind):
        raise _input_error(f"{where}: {what} (it is {_JSON_NAMES[type(value)]})")
    return value


class Run:
    """A run folder: its effective configuration, summary, frame records and scan path.

    frames: one dict a frame, as in frames.jsonl (boxes in input pixels; a stereo run's targets
    have disparity_px and disparity_sd_px, with a calibration position_m and position_sd_m,
    absent otherwise); targets_frame() and
    frames_frame(): the same as pandas DataFrames (one row a target a frame; one row a frame);
    map(kind, frame): a dumped map ("saliency", "inhibition", "inhibited", "features/mcg").
    """

    def __init__(self, folder):
        self.dir = os.fspath(folder)
        records = os.path.join(self.dir, "frames.jsonl")
        if not os.path.lexists(records):
            raise _input_error(f"{self.dir}: not a run folder (no frames.jsonl)")
        # Every line as `attend eval` reads it (the C++ reader: what it refuses, read_run
        # refuses, with the same message), then as JSON for the dicts.
        _attend._check_frame_records(records)
        self.frames = []
        for number, line in _lines(records):
            if line.strip():
                self.frames.append(_parse(line, f"{records}:{number}",
                                          "not a frame record", dict))
        self.summary = self._json("summary.json", {}, dict)
        self.scanpath = self._json("scanpath.json", [], list)
        self.config = ""
        config = os.path.join(self.dir, "config.yaml")
        if os.path.lexists(config):
            _attend._check_run_config(config)
            self.config = _text(config)

    def _json(self, name, fallback, kind):
        path = os.path.join(self.dir, name)
        if not os.path.lexists(path):
            return fallback
        _attend._check_regular_file(path)
        return _parse(_text(path), path, "not " + ("a JSON object" if kind is dict
                                                    else "a JSON list"), kind)

    def __repr__(self):
        return f"<attend.Run {self.dir}: {len(self.frames)} frames>"

    def target_rows(self):
        """One dict a target a frame: frame, id, x, y, w, h, area, saliency, state, kind, ...,
        and the depth columns of DEPTH_COLUMNS (None where the record has no depth: a mono
        run, a target not seen in the frame, an older record)."""
        rows = []
        for record in self.frames:
            for target in record.get("targets", []):
                row = {"frame": record["frame"]}
                for key, value in target.items():
                    if key == "bbox":
                        row.update(zip(("x", "y", "w", "h"), value))
                    elif key not in ("position_m", "position_sd_m"):
                        row[key] = value
                row.update(target_depth(target))
                row["new"] = target["id"] in record.get("new", [])
                rows.append(row)
        return rows

    def targets_frame(self):
        """The targets as a pandas DataFrame (pandas must be installed); the depth columns
        (DEPTH_COLUMNS) are floats, NaN where a record has none."""
        import pandas
        frame = pandas.DataFrame(self.target_rows())
        if frame.empty:
            return pandas.DataFrame(columns=TARGET_COLUMNS + list(DEPTH_COLUMNS))
        for column in DEPTH_COLUMNS:
            frame[column] = pandas.to_numeric(frame[column], errors="coerce").astype(float)
        return frame

    def frames_frame(self):
        """One row a frame: frame, targets, visible targets, new, inhibited fraction and each
        stage's milliseconds (timing.<stage>)."""
        import pandas
        rows = []
        for record in self.frames:
            row = {"frame": record["frame"], "targets": len(record.get("targets", [])),
                   "new": len(record.get("new", []))}
            if "inhibited_fraction" in record:
                row["inhibited_fraction"] = record["inhibited_fraction"]
            for stage, ms in record.get("timings_ms", {}).items():
                row[f"timing.{stage}"] = ms
            rows.append(row)
        return pandas.DataFrame(rows)

    def map(self, kind, frame):
        """A dumped map of a frame (PFM), float32 at the working size."""
        path = os.path.join(self.dir, kind, f"{frame:06d}.pfm")
        if not os.path.isfile(path):
            raise _input_error(f"{path}: no such map (output.dump and output.map_formats say "
                             "which maps a run writes)")
        return _attend.read_pfm(path)


def read_run(folder):
    """The run folder's records (attend.Run)."""
    return Run(folder)
