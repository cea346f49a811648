"""Reading a run folder (SPEC 3.3) into Python objects and, with pandas, DataFrames."""

import json
import os

from . import _attend


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
        self.config = ""
        config = os.path.join(self.dir, "config.yaml")
        if os.path.isfile(config):
            with open(config, encoding="utf-8") as file:
                self.config = file.read()

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
        return _attend.read_pfm(path)


def read_run(folder):
    """The run folder's records (attend.Run)."""
    return Run(folder)
