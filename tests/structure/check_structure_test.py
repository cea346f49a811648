#!/usr/bin/env python3
"""The structure check (scripts/check_structure.py) finds each kind of breach it is for, and
nothing in a tree that keeps the rules: a small tree is written whose breaches are known."""

import os
import subprocess
import sys
import tempfile

SCRIPT = os.path.join(os.path.dirname(__file__), "..", "..", "scripts", "check_structure.py")


def write(root, path, text):
    os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
    with open(os.path.join(root, path), "w", encoding="utf-8") as f:
        f.write(text)


def function(name, body_lines, reason=False):
    """A function of body_lines + 3 lines, with a comment above it."""
    head = "// One function: a table.\n" if reason else "// Does a thing.\n"
    body = "".join(f"  x += {i};\n" for i in range(body_lines))
    return f"{head}int {name}(int x) {{\n{body}  return x;\n}}\n"


def check(root):
    run = subprocess.run([sys.executable, SCRIPT, root], capture_output=True, text=True)
    return run.returncode, run.stdout


def main():
    failures = []
    with tempfile.TemporaryDirectory() as root:
        write(root, "CMakeLists.txt", "set(ATTEND_LAYERS util config io)\n")
        write(root, "util/a.h", "#pragma once\nint A(int x);\n")
        write(root, "util/a.cc", '#include "util/a.h"\n' + function("A", 50))
        write(root, "io/b.h", "#pragma once\n")
        write(root, "io/b.cc", '#include "io/b.h"\n' + function("Fits", 77) +
              function("Excused", 100, reason=True))
        write(root, "config/r.cc", "double v = block.GetDouble(\"k\", 1.0);\n")
        write(root, "tests/long_test.cc", "\n" * 700)
        status, out = check(root)
        if status != 0 or "0 breaches" not in out:
            failures.append(f"a clean tree: status {status}, output:\n{out}")

        write(root, "util/big.cc", "int x;\n" * 601)
        write(root, "io/c.cc", '#include "io/c.h"\n' + function("TooLong", 78))
        write(root, "io/c.h", '#pragma once\n#include "io/d.h"\n')
        write(root, "io/d.h", "#pragma once\n")
        write(root, "io/d.cc", '#include "io/d.h"\n#include "io/c.h"\n')
        write(root, "util/up.cc", '#include "io/b.h"\n')
        write(root, "io/read.cc", "double v = block.GetInt(\"k\", 1);\nauto n = YAML::Load(t);\n")
        status, out = check(root)
        expected = ["util/big.cc: 601 lines", "io/c.cc:3: TooLong is 81 lines",
                    "include cycle between the units io/c, io/d",
                    "util/up.cc:1: includes io/b.h, a layer above util/",
                    "io/read.cc:1: .GetInt outside config/", "io/read.cc:2: YAML::Load outside config/",
                    "6 breaches"]
        if status != 1:
            failures.append(f"a tree with breaches: status {status}, not 1")
        for line in expected:
            if line not in out:
                failures.append(f"missing '{line}' in:\n{out}")
    for failure in failures:
        print("FAILED:", failure)
    print(f"{0 if failures else 1} passed, {1 if failures else 0} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
