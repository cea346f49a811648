#!/usr/bin/env python3
"""Converts a published eye-tracking dataset to attend's fixation layout (docs/FIXATIONS.md,
"Dataset layout"), which `attend eval-fixations --dataset` reads:

  scripts/convert_fixations.py --format {mit1003,osie,cat2000,crowd} SRC --out DATASET
                               [--symlink] [--overwrite] [--keep-first]

DATASET/stimuli/<id>.<ext> is each stimulus (copied, or with --symlink linked), its id kept
(CAT2000: <Category>_<image>); DATASET/fixations/<id>.txt has a `#` header naming the source,
then one fixation a line, `subject x y duration_ms` (CAT2000: `subject x y`), each observer's in
viewing order, x the column and y the row in 1-based pixels of the stimulus. SRC is the folder
the dataset unpacks to:

  mit1003  SRC/ALLSTIMULI/<image>.jpeg and SRC/DATA/<subject>/<image>.mat (raw 240 Hz eye
           samples; fixations found by the acceleration rule of the dataset's checkFixations.m,
           SaccadeRule below; the first fixation, on the central cross, left out unless
           --keep-first)
  osie     SRC/data/eye/fixations.mat and SRC/data/stimuli/<image>.jpg (Xu et al., JoV 2014)
  crowd    the same layout ("Saliency in Crowd", Jiang et al., ECCV 2014)
  cat2000  SRC/Stimuli/<Category>/<image>.jpg and SRC/FIXATIONLOCS/<Category>/<image>.mat
           (a binary map of the fixated pixels of all observers: written as subject 0, one line
           a non-zero pixel, in raster order; the map has no order and no observers)

(SRC may also be the data/ folder itself for osie and crowd, or the folder holding trainSet/
for cat2000.) Needs only numpy and scipy (Debian's python3-numpy, python3-scipy); a MATLAB v7.3
(HDF5) file is refused with a message (docs/FIXATIONS.md says which formats are known not to be).

Exit status (SPEC 3.2): 0 done; 2 bad flags, or an output folder in the way (--overwrite);
3 bad input data, named as `FILE: FIELD: what is wrong`; 1 internal error.
"""

import argparse
import dataclasses
import os
import shutil
import sys
from pathlib import Path

try:
    import numpy as np
    import scipy.io  # noqa: F401 (load_mat's loadmat)
except ImportError as missing:
    sys.exit(f"convert_fixations: error: {missing.name} is missing from {sys.executable}: this "
             "script needs numpy and scipy (Debian's python3-numpy and python3-scipy, which "
             "scripts/install_deps.sh installs); run it with /usr/bin/python3")

# The stimulus extensions attend's reader takes (eval/fixation_data.cc), compared in lower case.
STIMULUS_EXTENSIONS = (".jpg", ".jpeg", ".png", ".ppm", ".pgm", ".bmp")
FORMATS = ("mit1003", "osie", "cat2000", "crowd")
PROGRAM = "convert_fixations"


class InputError(Exception):
    """Bad input data (exit 3); the message names the file and the field."""


class UsageError(Exception):
    """Bad flags or an output folder in the way (exit 2)."""


@dataclasses.dataclass
class Item:
    """One stimulus and its fixations, as written to DATASET."""
    id: str
    stimulus: Path
    rows: list            # (subject, x, y) or (subject, x, y, duration_ms), in the file's order
    header: str           # the `#` line's text after the column names


# ---------------------------------------------------------------------------------------------
# MATLAB files

def _plain(value):
    """Structs as dicts and cells as lists, all the way down: scipy's simplify_cells leaves a
    struct behind in a cell that also holds an empty matrix."""
    if hasattr(value, "_fieldnames"):  # scipy.io.matlab's mat_struct
        return {name: _plain(getattr(value, name)) for name in value._fieldnames}
    if isinstance(value, dict):
        return {key: _plain(item) for key, item in value.items()}
    if isinstance(value, list) or (isinstance(value, np.ndarray) and value.dtype == object):
        return [_plain(item) for item in (value if isinstance(value, list) else value.ravel())]
    return value


def load_mat(path):
    """A MATLAB file's variables, structs as dicts and cells as lists (as scipy's
    simplify_cells: a one-element array or cell is its element)."""
    from scipy.io import loadmat
    try:
        return _plain(loadmat(str(path), simplify_cells=True))
    except NotImplementedError:
        raise InputError(f"{path}: a MATLAB v7.3 (HDF5) file, which this converter does not "
                         "read; save it again in MATLAB with save(..., '-v7')") from None
    except Exception as error:  # scipy raises many kinds on a damaged file
        raise InputError(f"{path}: not a readable MATLAB file ({type(error).__name__}: "
                         f"{error})") from None


def variables(mat):
    return {k: v for k, v in mat.items() if not k.startswith("__")}


def as_list(value):
    """A cell array or struct array as a list (one element comes back squeezed)."""
    if isinstance(value, list):
        return value
    if isinstance(value, np.ndarray) and value.size == 0:
        return []
    return [value]


def field(struct, name, where, path):
    if not isinstance(struct, dict):
        raise InputError(f"{path}: {where}: expected a struct, got {type(struct).__name__}")
    if name not in struct:
        have = ", ".join(sorted(struct)) or "none"
        raise InputError(f"{path}: {where}.{name}: missing (fields: {have})")
    return struct[name]


def numbers(value, where, path):
    """A numeric vector (a scalar or an empty matrix too) as a 1-D float array, all finite."""
    if isinstance(value, (list, dict, str)) or (isinstance(value, np.ndarray)
                                                and value.dtype.kind not in "biuf"):
        raise InputError(f"{path}: {where}: expected numbers, got {type(value).__name__}")
    array = np.atleast_1d(np.asarray(value, dtype=float))
    if array.ndim > 1 and array.size and min(array.shape) > 1:
        raise InputError(f"{path}: {where}: expected a vector, got a {array.shape} matrix")
    array = array.ravel()
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        raise InputError(f"{path}: {where}({bad[0] + 1}): not a finite number")
    return array


# ---------------------------------------------------------------------------------------------
# MIT1003: fixations from raw eye samples

@dataclasses.dataclass(frozen=True)
class SaccadeRule:
    """The fixation rule of MIT1003's checkFixations.m (its DatabaseCode; B. Hidalgo-Sotelo,
    2006), as its header and comments document it, with its parameter values. A saccade is an
    acceleration of the eye followed by a deceleration; the fixations are what lies between."""
    sampling_hz: float = 240.0         # the eye tracker's sample rate (ISCAN ETL 400)
    px_per_degree: float = 34.0        # checkFixations' pixels per degree of visual angle
    threshold_deg_per_s: float = 6.0   # the acceleration criterion is px_per_degree times this
    window: int = 4                    # samples per velocity window (16.7 ms), windows 1 apart
    min_fixation_ms: float = 50.0      # a shorter fixation between two saccades joins them
    deceleration_search: int = 25      # samples after an acceleration to find its deceleration

    def check(self):
        """Names the first field out of range, or returns None."""
        if not self.sampling_hz > 0:
            return "sampling_hz must be > 0"
        if not self.px_per_degree > 0 or not self.threshold_deg_per_s > 0:
            return "px_per_degree and threshold_deg_per_s must be > 0"
        if self.window < 1 or self.deceleration_search < 1:
            return "window and deceleration_search must be >= 1"
        if self.min_fixation_ms < 0:
            return "min_fixation_ms must be >= 0"
        return None


def _runs(mask):
    """(first, last) index pairs of the runs of True in a boolean vector."""
    padded = np.concatenate(([False], mask, [False])).astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    return list(zip(edges[0::2], edges[1::2] - 1))


def acceleration(xy, rule):
    """Per sample, the change in eye speed (px/s) between two windows of `window` samples one
    sample apart, on the sample-to-sample distance smoothed by a `window`-sample running mean.
    Zero where the windows would leave the recording; NaN next to a missing sample."""
    n = len(xy)
    w = rule.window
    if n == 0:
        return np.zeros(0)
    step = np.zeros(n)
    if n > 1:
        step[1:] = np.hypot(np.diff(xy[:, 0]), np.diff(xy[:, 1]))
    smooth = np.convolve(step, np.ones(w) / w)[:n]  # causal: the mean of the last w steps
    accel = np.zeros(n)
    # Window k spans smooth[k .. k+w]; the next window drops smooth[k] and adds smooth[k+w+1].
    if n > w + 1:
        accel[:n - w - 1] = (smooth[w + 1:] - smooth[:n - w - 1]) * rule.sampling_hz / w
    return accel


def saccades(accel, rule):
    """(first, last) samples of each saccade: a run of at least two samples accelerating past
    the criterion, to the last sample of the first run decelerating past it within
    `deceleration_search` samples. A run with no deceleration is no saccade, unless the
    recording ends first (the trial ends in a saccade)."""
    criterion = rule.px_per_degree * rule.threshold_deg_per_s
    with np.errstate(invalid="ignore"):
        speeding = accel > criterion
        slowing = accel < -criterion
    last = len(accel) - 1
    found = []
    for first, end in _runs(speeding):
        if end == first or (found and first <= found[-1][1]):
            continue  # a lone sample, or inside the previous saccade
        stop = None
        for j in range(end + 1, min(end + rule.deceleration_search, last - 1) + 1):
            if slowing[j] and not slowing[j + 1]:
                stop = j
                break
        if stop is None and end + rule.deceleration_search >= last - 1:
            stop = last
        if stop is not None:
            found.append((first, stop))
    return found


def detect_fixations(samples, rule=SaccadeRule()):
    """Fixations of one recording (N x 2 eye positions in pixels, NaN or negative where the
    eye was lost: the MIT1003 data mark blinks with negative positions) as an array of rows
    (x, y, onset_ms, duration_ms): each the median position of its samples. A missing sample
    belongs to no fixation (a blink ends one). A fixation that does not start the recording and
    lasts under min_fixation_ms is dropped."""
    problem = rule.check()
    if problem:
        raise ValueError(f"SaccadeRule: {problem}")
    xy = np.array(samples, dtype=float).reshape(-1, 2)
    with np.errstate(invalid="ignore"):
        missing = ~np.isfinite(xy).all(axis=1) | (xy < 0).any(axis=1)
    xy[missing] = np.nan
    moving = missing.copy()
    for first, last in saccades(acceleration(xy, rule), rule):
        moving[first:last + 1] = True
    shortest = round(rule.min_fixation_ms * rule.sampling_hz / 1000.0)
    rows = []
    for first, last in _runs(~moving):
        count = last - first + 1
        if first > 0 and count < shortest:
            continue
        rows.append((float(np.median(xy[first:last + 1, 0])),
                     float(np.median(xy[first:last + 1, 1])),
                     1000.0 * first / rule.sampling_hz, 1000.0 * count / rule.sampling_hz))
    return np.array(rows, dtype=float).reshape(-1, 4)


def eye_samples(path, stem):
    """DATA(1).eyeData of one MIT1003 file: a struct named after the image (the only variable
    when MATLAB shortened the name) with DATA(1).eyeData, N x 2 positions (more columns are
    ignored)."""
    found = variables(load_mat(path))
    if stem in found:
        name = stem
    elif len(found) == 1:
        name = next(iter(found))
    else:
        raise InputError(f"{path}: expected one variable named {stem}, found "
                         f"{', '.join(sorted(found)) or 'none'}")
    data = as_list(field(found[name], "DATA", name, path))
    if not data:
        raise InputError(f"{path}: {name}.DATA: empty")
    eye = field(data[0], "eyeData", f"{name}.DATA(1)", path)
    where = f"{name}.DATA(1).eyeData"
    if not isinstance(eye, np.ndarray) or eye.dtype.kind not in "biuf":
        raise InputError(f"{path}: {where}: expected numbers, got {type(eye).__name__}")
    if eye.size == 0:
        return np.zeros((0, 2))
    if eye.ndim == 1 and eye.size == 2:  # one sample, squeezed by the loader
        eye = eye.reshape(1, 2)
    if eye.ndim != 2 or eye.shape[1] < 2:  # a single row or column comes squeezed to 1-D
        got = f"{eye.size} values in one row or column" if eye.ndim == 1 else \
            f"shape {'x'.join(map(str, eye.shape))}"
        raise InputError(f"{path}: {where}: expected N x 2 eye positions, got {got}")
    return eye[:, :2].astype(float)


def stimuli_of(folder):
    """The files of `folder` whose extension attend reads, sorted by name."""
    return sorted(p for p in folder.iterdir()
                  if p.is_file() and p.suffix.lower() in STIMULUS_EXTENSIONS)


def read_mit1003(src, keep_first, skipped):
    stimuli_dir, data_dir = src / "ALLSTIMULI", src / "DATA"
    for folder in (stimuli_dir, data_dir):
        if not folder.is_dir():
            raise InputError(f"{src}: no {folder.name}/ folder (MIT1003's layout: ALLSTIMULI/, "
                             "DATA/<subject>/)")
    subjects = sorted(p.name for p in data_dir.iterdir() if p.is_dir())
    if not subjects:
        raise InputError(f"{data_dir}: no subject folders")
    return _mit1003_items(stimuli_of(stimuli_dir), data_dir, subjects, keep_first, skipped)


def _mit1003_items(stimuli, data_dir, subjects, keep_first, skipped):
    names = ", ".join(f"{i} {s}" for i, s in enumerate(subjects))
    first = 0 if keep_first else 1
    for stimulus in stimuli:
        rows = []
        for index, subject in enumerate(subjects):
            path = data_dir / subject / (stimulus.stem + ".mat")
            if not path.is_file():
                continue
            fixations = detect_fixations(eye_samples(path, stimulus.stem))[first:]
            rows += [(index, x, y, duration) for x, y, _, duration in fixations]
        if not rows:
            skipped.append(f"{stimulus.name}: no subject's data")
            continue
        header = (f"MIT1003 DATA/<subject>/{stimulus.stem}.mat: fixations by checkFixations' "
                  f"rule (scripts/convert_fixations.py), {'with' if keep_first else 'without'} "
                  f"the first (central) one, one a line, each subject's in viewing order; "
                  f"subjects: {names}")
        yield Item(stimulus.stem, stimulus, rows, header)


# ---------------------------------------------------------------------------------------------
# OSIE and Saliency in Crowd: one fixations.mat of the NUS VIP lab's layout

def read_nus(src, label, skipped):
    """fixations.mat's `fixations`: a cell array, one struct an image, with `img` (the stimulus
    file name) and `subjects` (a cell array, one struct an observer, with vectors fix_x, fix_y
    and fix_duration: 1-based pixels and milliseconds, in viewing order)."""
    data = src / "data" if (src / "data" / "eye").is_dir() else src
    path, stimuli_dir = data / "eye" / "fixations.mat", data / "stimuli"
    if not path.is_file():
        raise InputError(f"{src}: no data/eye/fixations.mat ({label}'s layout)")
    if not stimuli_dir.is_dir():
        raise InputError(f"{src}: no data/stimuli/ folder ({label}'s layout)")
    found = variables(load_mat(path))
    if "fixations" not in found:
        raise InputError(f"{path}: fixations: missing (variables: "
                         f"{', '.join(sorted(found)) or 'none'})")
    return _nus_items(as_list(found["fixations"]), path, stimuli_dir, label, skipped)


def _nus_items(images, path, stimuli_dir, label, skipped):
    seen = set()
    for i, image in enumerate(images, 1):
        where = f"fixations{{{i}}}"
        name = field(image, "img", where, path)
        if not isinstance(name, str) or not name:
            raise InputError(f"{path}: {where}.img: expected a file name")
        stimulus = stimuli_dir / name
        if stimulus.stem in seen:
            raise InputError(f"{path}: {where}.img: {name} again")
        seen.add(stimulus.stem)
        rows = []
        for j, subject in enumerate(as_list(field(image, "subjects", where, path))):
            if isinstance(subject, np.ndarray) and subject.size == 0:
                continue  # an empty cell: an observer without data
            at = f"{where}.subjects{{{j + 1}}}"
            xs = numbers(field(subject, "fix_x", at, path), f"{at}.fix_x", path)
            ys = numbers(field(subject, "fix_y", at, path), f"{at}.fix_y", path)
            ds = numbers(field(subject, "fix_duration", at, path), f"{at}.fix_duration", path)
            for other, values in (("fix_y", ys), ("fix_duration", ds)):
                if len(values) != len(xs):
                    raise InputError(f"{path}: {at}.{other}: {len(values)} values, fix_x has "
                                     f"{len(xs)}")
            if (ds < 0).any():
                raise InputError(f"{path}: {at}.fix_duration({np.argmax(ds < 0) + 1}): negative")
            rows += [(j, x, y, d) for x, y, d in zip(xs, ys, ds)]
        if not rows:
            skipped.append(f"{name}: no subject's fixations")
            continue
        if not stimulus.is_file():
            skipped.append(f"{name}: no stimulus {stimulus}")
            continue
        if stimulus.suffix.lower() not in STIMULUS_EXTENSIONS:
            skipped.append(f"{name}: attend does not read {stimulus.suffix} stimuli")
            continue
        header = (f"{label} {path.name} {where} ({name}): one fixation a line, each subject's "
                  "in viewing order; subject: position in its subjects cell, from 0")
        yield Item(stimulus.stem, stimulus, rows, header)


# ---------------------------------------------------------------------------------------------
# CAT2000: binary fixation maps

def fixation_map(path):
    found = variables(load_mat(path))
    if "fixLocs" in found:
        name = "fixLocs"
    elif len(found) == 1:
        name = next(iter(found))
    else:
        raise InputError(f"{path}: fixLocs: missing (variables: "
                         f"{', '.join(sorted(found)) or 'none'})")
    locations = found[name]
    if not isinstance(locations, np.ndarray) or locations.dtype.kind not in "biuf" \
            or locations.ndim != 2:
        shape = getattr(locations, "shape", None)
        raise InputError(f"{path}: {name}: expected a 2-D binary map, got "
                         f"{type(locations).__name__} {shape if shape is not None else ''}"
                         .rstrip())
    if not np.isfinite(locations).all():
        raise InputError(f"{path}: {name}: not finite everywhere")
    return locations


def read_cat2000(src, skipped):
    root = src / "trainSet" if (src / "trainSet" / "Stimuli").is_dir() else src
    stimuli_dir, maps_dir = root / "Stimuli", root / "FIXATIONLOCS"
    if not stimuli_dir.is_dir():
        raise InputError(f"{src}: no Stimuli/ folder (CAT2000's layout: Stimuli/<Category>/)")
    if not maps_dir.is_dir():
        raise InputError(f"{src}: no FIXATIONLOCS/ folder (CAT2000's test set has none)")
    return _cat2000_items(stimuli_dir, maps_dir, skipped)


def _cat2000_items(stimuli_dir, maps_dir, skipped):
    for category in sorted(p for p in stimuli_dir.iterdir() if p.is_dir()):
        for stimulus in stimuli_of(category):
            path = maps_dir / category.name / (stimulus.stem + ".mat")
            if not path.is_file():
                skipped.append(f"{category.name}/{stimulus.name}: no {path}")
                continue
            rows_y, cols_x = np.nonzero(fixation_map(path))  # raster order
            rows = [(0, float(x + 1), float(y + 1)) for y, x in zip(rows_y, cols_x)]
            if not rows:
                skipped.append(f"{category.name}/{stimulus.name}: no fixated pixel in {path}")
                continue
            header = (f"CAT2000 FIXATIONLOCS/{category.name}/{path.name}: one fixated pixel a "
                      "line, all observers pooled without order or observer, subject 0")
            yield Item(f"{category.name}_{stimulus.stem}", stimulus, rows, header)


# ---------------------------------------------------------------------------------------------
# Writing

def _number(value, decimals):
    text = f"{value:.{decimals}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def prepare_output(out, overwrite):
    """DATASET/stimuli and DATASET/fixations, empty: folders holding files are an error unless
    --overwrite, which empties them (nothing else in DATASET is touched)."""
    if out.exists() and not out.is_dir():
        raise UsageError(f"{out}: exists and is not a folder")
    for name in ("stimuli", "fixations"):
        folder = out / name
        if folder.is_symlink() or (folder.exists() and not folder.is_dir()):
            raise UsageError(f"{folder}: exists and is not a folder")
        try:
            if folder.is_dir() and any(folder.iterdir()):
                if not overwrite:
                    raise UsageError(f"{folder}: not empty (--overwrite replaces its files)")
                shutil.rmtree(folder)
            folder.mkdir(parents=True, exist_ok=True)
        except OSError as error:
            raise UsageError(f"{folder}: cannot be made ready: {error.strerror}") from None


def fixation_text(item, stimulus_name):
    """The fixation file's text: the header, then one line a row."""
    columns = "subject x y duration_ms" if item.rows and len(item.rows[0]) == 4 else "subject x y"
    lines = [f"# {columns}  ({item.header}; x column, y row, 1-based pixels of "
             f"stimuli/{stimulus_name})"]
    for row in item.rows:
        text = [str(int(row[0])), _number(row[1], 3), _number(row[2], 3)]
        if len(row) == 4:
            text.append(_number(row[3], 1))
        lines.append(" ".join(text))
    return "\n".join(lines) + "\n"


def write_item(item, out, symlink):
    target = out / "stimuli" / (item.id + item.stimulus.suffix)
    if target.exists() or target.is_symlink():
        raise InputError(f"{item.stimulus}: a second stimulus with id {item.id}")
    if not os.access(item.stimulus, os.R_OK):
        raise InputError(f"{item.stimulus}: cannot be read")
    try:
        if symlink:
            os.symlink(item.stimulus.resolve(), target)
        else:
            shutil.copyfile(item.stimulus, target)
        (out / "fixations" / (item.id + ".txt")).write_text(fixation_text(item, target.name),
                                                            encoding="utf-8")
    except OSError as error:
        raise UsageError(f"{out}: cannot write {item.id}: {error.strerror}") from None


def convert(fmt, src, out, symlink=False, overwrite=False, keep_first=False):
    """Converts SRC (of format `fmt`) into DATASET; returns a one-line summary."""
    src, out = Path(src), Path(out)
    if not src.is_dir():
        raise InputError(f"{src}: no such folder")
    skipped = []
    if fmt == "mit1003":
        items = read_mit1003(src, keep_first, skipped)
    elif fmt == "cat2000":
        items = read_cat2000(src, skipped)
    else:
        items = read_nus(src, {"osie": "OSIE", "crowd": "Saliency in Crowd"}[fmt], skipped)
    prepare_output(out, overwrite)
    count = fixations = 0
    for item in items:
        write_item(item, out, symlink)
        count += 1
        fixations += len(item.rows)
    if count == 0:
        raise InputError(f"{src}: no stimulus with fixations")
    for reason in skipped:
        print(f"{PROGRAM}: note: skipped {reason}", file=sys.stderr)
    return (f"{fmt}: {count} stimuli, {fixations} fixations written to {out}"
            f"{f'; {len(skipped)} skipped' if skipped else ''}")


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="convert_fixations.py",
        description="Converts an eye-tracking dataset (MIT1003, OSIE, CAT2000, Saliency in "
                    "Crowd) to attend's fixation layout (docs/FIXATIONS.md): DATASET/stimuli/"
                    "<id>.<ext> and DATASET/fixations/<id>.txt.")
    parser.add_argument("--format", required=True, choices=FORMATS, help="the dataset's layout")
    parser.add_argument("src", metavar="SRC", help="the folder the dataset unpacks to")
    parser.add_argument("--out", required=True, metavar="DATASET", help="the folder to write")
    parser.add_argument("--symlink", action="store_true",
                        help="link the stimuli (absolute paths) instead of copying them")
    parser.add_argument("--overwrite", action="store_true",
                        help="empty DATASET/stimuli and DATASET/fixations first")
    parser.add_argument("--keep-first", action="store_true",
                        help="mit1003: keep each recording's first fixation (the central cross "
                             "the experiment made observers look at)")
    args = parser.parse_args(argv)  # exits 2 on bad flags
    try:
        if args.keep_first and args.format != "mit1003":
            raise UsageError("--keep-first: only for --format mit1003")
        print(convert(args.format, args.src, args.out, args.symlink, args.overwrite,
                      args.keep_first))
        return 0
    except UsageError as error:
        print(f"{PROGRAM}: error: {error}", file=sys.stderr)
        return 2
    except InputError as error:
        print(f"{PROGRAM}: error: {error}", file=sys.stderr)
        return 3
    except OSError as error:  # reading the source (writing raises UsageError)
        print(f"{PROGRAM}: error: {error.filename}: {error.strerror}", file=sys.stderr)
        return 3
    except Exception as error:  # a bug: one line, not a traceback
        print(f"{PROGRAM}: internal error: {type(error).__name__}: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
