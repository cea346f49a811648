"""Reading a run folder (SPEC 3.3) into Python objects and, with pandas, DataFrames."""

import json
import os

import numpy as np


def read_pfm(path):
    """A PFM file (the run's lossless maps) as a float32 array, top row first."""
    with open(path, "rb") as file:
        header = file.readline().strip()
        if header not in (b"Pf", b"PF"):
            raise ValueError(f"{path}: not a PFM file")
        width, height = (int(v) for v in file.readline().split())
        scale = float(file.readline().strip())
        channels = 1 if header == b"Pf" else 3
        data = np.fromfile(file, dtype="<f4" if scale < 0 else ">f4",
                           count=width * height * channels)
    if data.size != width * height * channels:
        raise ValueError(f"{path}: cut short")
    shape = (height, width) if channels == 1 else (height, width, 3)
    return np.ascontiguousarray(np.flipud(data.reshape(shape)).astype(np.float32))


def write_pfm(path, image):
    """Writes a float map (H x W, or H x W x 3) as PFM, the format of the run's lossless maps
    and of the saliency folders that attend eval-fixations scores."""
    data = np.asarray(image, dtype="<f4")
    if data.ndim not in (2, 3) or (data.ndim == 3 and data.shape[2] != 3):
        raise ValueError(f"{path}: a PFM map is H x W or H x W x 3, not {data.shape}")
    header = b"Pf" if data.ndim == 2 else b"PF"
    with open(path, "wb") as file:
        file.write(b"%s\n%d %d\n-1\n" % (header, data.shape[1], data.shape[0]))
        file.write(np.ascontiguousarray(np.flipud(data)).tobytes())


class Run:
    """A run folder: its effective configuration, summary, frame records and scan path.

    frames: one dict a frame, as in frames.jsonl (boxes in input pixels); targets_frame() and
    frames_frame(): the same as pandas DataFrames (one row a target a frame; one row a frame);
    map(kind, frame): a dumped map ("saliency", "inhibition", "inhibited", "features/mcg").
    """

    def __init__(self, folder):
        self.dir = os.fspath(folder)
        records = os.path.join(self.dir, "frames.jsonl")
        if not os.path.isfile(records):
            from . import InputError
            raise InputError(f"{self.dir}: not a run folder (no frames.jsonl)")
        self.frames = []
        with open(records, encoding="utf-8") as file:
            for number, line in enumerate(file, 1):
                if not line.strip():
                    continue
                try:
                    self.frames.append(json.loads(line))
                except json.JSONDecodeError as error:
                    from . import InputError
                    raise InputError(f"{records}:{number}: not a JSON record: {error}") from None
        self.summary = self._json("summary.json", {})
        self.scanpath = self._json("scanpath.json", [])
        config = os.path.join(self.dir, "config.yaml")
        self.config = open(config, encoding="utf-8").read() if os.path.isfile(config) else ""

    def _json(self, name, fallback):
        path = os.path.join(self.dir, name)
        if not os.path.isfile(path):
            return fallback
        with open(path, encoding="utf-8") as file:
            return json.load(file)

    def __repr__(self):
        return f"<attend.Run {self.dir}: {len(self.frames)} frames>"

    def target_rows(self):
        """One dict a target a frame: frame, id, x, y, w, h, area, saliency, state, kind, ..."""
        rows = []
        for record in self.frames:
            for target in record.get("targets", []):
                row = {"frame": record["frame"]}
                for key, value in target.items():
                    if key == "bbox":
                        row.update(zip(("x", "y", "w", "h"), value))
                    else:
                        row[key] = value
                row["new"] = target["id"] in record.get("new", [])
                rows.append(row)
        return rows

    def targets_frame(self):
        """The targets as a pandas DataFrame (pandas must be installed)."""
        import pandas
        columns = ["frame", "id", "x", "y", "w", "h", "area", "saliency", "state", "kind"]
        frame = pandas.DataFrame(self.target_rows())
        return frame if not frame.empty else pandas.DataFrame(columns=columns)

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
            from . import InputError
            raise InputError(f"{path}: no such map (output.dump and output.map_formats say "
                             "which maps a run writes)")
        return read_pfm(path)


def read_run(folder):
    """The run folder's records (attend.Run)."""
    return Run(folder)
