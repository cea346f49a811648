"""Fuzzing attend.read_run (issue 46, case 5; docs/FUZZING.md, "Python"): a valid run folder's
frames.jsonl, summary.json, scanpath.json and config.yaml mutated (bit flips, truncation, lines
dropped or doubled, values of another type, huge numbers, deep nesting, binary bytes, other
line ends), each then read by read_run and the Run's methods, which must either work or raise
attend.InputError: anything else (a KeyError, a UnicodeDecodeError, a crash) is a finding.

Deterministic: a fixed seed and count (ATTEND_FUZZ_SEED, ATTEND_FUZZ_ITERATIONS for longer
runs); a finding names its iteration and mutations, and leaves the input in the test's folder.
"""

import json
import os
import random
import re
import shutil

import attend

SEED = int(os.environ.get("ATTEND_FUZZ_SEED", "46"))
ITERATIONS = int(os.environ.get("ATTEND_FUZZ_ITERATIONS", "600"))
FILES = ["frames.jsonl"] * 4 + ["summary.json", "scanpath.json", "config.yaml"]

HUGE = ["1e400", "-1e400", "1e-400", "18446744073709551616", "-9223372036854775809",
        "2147483648", "-2147483649", "99999999999999999999999999999999999999", "1.0e+308"]
OTHER_VALUES = ["2", 2.5, None, True, False, [], {}, [1, 2, 3], {"a": 1}, "x" * 40, -1,
                2 ** 31, 2 ** 63, -(2 ** 63) - 1, "", [[0, 0, 1, 1]], {"id": 1}]


def nested(rng):
    """A value nested 2 to 3000 levels deep, as JSON text."""
    depth = rng.choice([2, 20, 200, 3000])
    opening, closing = rng.choice([("[", "]"), ('{"a":', "}")])
    return opening * depth + "0" + closing * depth


def nodes(value, path=()):
    """Every (path, value) of a JSON value, itself first."""
    yield path, value
    if isinstance(value, dict):
        for key, item in value.items():
            yield from nodes(item, path + (key,))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            yield from nodes(item, path + (index,))


def replaced(value, path, new):
    if not path:
        return new
    value[path[0]] = replaced(value[path[0]], path[1:], new) if len(path) > 1 else new
    return value


def structural(rng, text):
    """A JSON text with one value replaced (another type, a huge number, deep nesting) or one
    key dropped; text that is not JSON is returned as it is."""
    try:
        value = json.loads(text)
    except (ValueError, RecursionError):
        return text, "not JSON"
    path, node = rng.choice(list(nodes(value)))
    kind = rng.choice(["type", "huge", "nest", "drop"])
    if kind == "drop" and isinstance(node, dict) and node:
        del node[rng.choice(list(node))]
        return json.dumps(value), f"drop a key at {path}"
    if kind == "nest":
        new = nested(rng)
    elif kind == "huge":
        new = rng.choice(HUGE)
    else:
        new = json.dumps(rng.choice(OTHER_VALUES))
    marker = "\0MARK\0"
    out = json.dumps(replaced(value, path, marker)).replace(json.dumps(marker), new)
    return out, f"{kind} at {path}"


def mutate(rng, name, data):
    """One mutation of a file's bytes; returns the bytes and what was done."""
    choices = ["flip", "truncate", "binary", "line ends"]
    if name != "config.yaml":
        choices += ["structure"] * 4
    if name == "frames.jsonl":
        choices += ["drop line", "double line", "swap lines"]
    kind = rng.choice(choices) if data else "binary"
    if kind == "flip":
        data = bytearray(data)
        for _ in range(rng.randint(1, 8)):
            data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
        return bytes(data), kind
    if kind == "truncate":
        return data[:rng.randrange(len(data) + 1)], kind
    if kind == "binary":
        at = rng.randrange(len(data) + 1)
        junk = bytes(rng.randrange(256) for _ in range(rng.choice([1, 4, 64])))
        return data[:at] + junk + data[at:], kind
    if kind == "line ends":
        return data.replace(b"\n", rng.choice([b"\r\n", b"\r", b"\n\n", b" \n"])), kind
    lines = data.split(b"\n")
    if kind == "structure":
        if name == "frames.jsonl":
            index = rng.randrange(len(lines))
            text, done = structural(rng, lines[index].decode("utf-8", "replace"))
            lines[index] = text.encode()
            return b"\n".join(lines), f"line {index + 1}: {done}"
        text, done = structural(rng, data.decode("utf-8", "replace"))
        return text.encode(), done
    a, b = rng.randrange(len(lines)), rng.randrange(len(lines))
    if kind == "drop line":
        del lines[a]
    elif kind == "double line":
        lines.insert(a, lines[a])
    else:
        lines[a], lines[b] = lines[b], lines[a]
    return b"\n".join(lines), f"{kind} {a + 1}"


def exercise(folder):
    """read_run and every method of the Run: "read", or "refused" on InputError."""
    try:
        run = attend.read_run(folder)
        repr(run)
        run.target_rows()
        run.targets_frame()
        run.frames_frame()
        for record in run.frames[:2]:
            try:
                run.map("saliency", record["frame"])
            except attend.InputError:
                pass
        return "read"
    except attend.InputError:
        return "refused"


def test_read_run_takes_mutated_run_folders_or_refuses_them_with_input_error(cli_run,
                                                                             tmp_path):
    folder = tmp_path / "run"
    os.makedirs(folder)
    originals = {}
    for name in set(FILES):
        shutil.copy(os.path.join(cli_run, name), folder / name)
        originals[name] = (folder / name).read_bytes()
    rng = random.Random(SEED)
    outcomes = {"read": 0, "refused": 0}
    findings = []
    for iteration in range(ITERATIONS):
        name = rng.choice(FILES)
        data, done = originals[name], []
        for _ in range(rng.choice([1, 1, 2, 3])):
            data, what = mutate(rng, name, data)
            done.append(what)
        (folder / name).write_bytes(data)
        try:
            outcomes[exercise(folder)] += 1
        except Exception as error:  # noqa: BLE001: every other exception is a finding
            kept = tmp_path / f"finding-{iteration}-{name}"
            kept.write_bytes(data)
            findings.append(f"iteration {iteration} ({name}: {'; '.join(done)}): "
                            f"{type(error).__name__}: {str(error)[:300]} (input: {kept})")
            if len(findings) >= 5:
                break
        (folder / name).write_bytes(originals[name])
    assert not findings, f"seed {SEED}:\n" + "\n".join(findings)
    # Both answers are exercised: mutations that all refused (or all passed) would test little.
    assert outcomes["read"] > ITERATIONS // 10 and outcomes["refused"] > ITERATIONS // 10, \
        outcomes
