#!/usr/bin/env python3
"""Checks the shape of attend's library code (CONTRIBUTING.md, "How the code is laid out").

  scripts/check_structure.py [ROOT]

Library code is every .h and .cc below the layer folders (CMakeLists.txt's ATTEND_LAYERS) and
python/; tests/, bench/, fuzz/, examples/ and sanitizers/ are not library code. The rules:

  1. no library file over 600 lines;
  2. no function over 80 lines unless the comment right above it has a line starting with
     "One function:" that says why it reads best whole;
  3. no include cycle between units (a unit is a .h with its .cc; a header without a .cc is
     part of the unit whose files share it), and no include that runs
     up the layers (a folder includes only itself and the folders before it in ATTEND_LAYERS);
  4. option values are read only through field tables: no call of ParamBlock's accessors
     (.GetDouble, .GetInt, .GetString, .GetChoice, ...) or of YAML::Load outside config/.

Functions are found with universal-ctags (scripts/install_deps.sh installs it), which gives
each function's first and last line. Prints one line per breach, naming file and line, and
exits 1 when there is any, 0 when there is none, 2 when it cannot run (77, which ctest
counts as skipped, when ctags is missing).
"""

import os
import re
import shutil
import subprocess
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 80
REASON = "One function:"
NOT_LIBRARY = {"tests", "bench", "fuzz", "examples", "sanitizers", "build"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
# ParamBlock's accessors (config/param_block.h) and yaml-cpp's parser.
OPTION_CALL = re.compile(r"(\.Get(?:Bool|Int|Double|String|Choice|Doubles|Ints|Strings)\b|YAML::Load\b)\s*\(")


class MissingTool(RuntimeError):
    pass


def read_layers(root):
    """The layer folders in order, from the top CMakeLists.txt's ATTEND_LAYERS."""
    with open(os.path.join(root, "CMakeLists.txt"), encoding="utf-8") as f:
        text = f.read()
    match = re.search(r"set\(ATTEND_LAYERS([^)]*)\)", text)
    if not match:
        raise RuntimeError("CMakeLists.txt: no set(ATTEND_LAYERS ...)")
    return match.group(1).split()


def library_files(root, folders):
    files = []
    for folder in folders:
        for base, dirs, names in os.walk(os.path.join(root, folder)):
            dirs[:] = sorted(d for d in dirs if d not in NOT_LIBRARY and d != "attend")
            for name in sorted(names):
                if name.endswith((".h", ".cc")):
                    files.append(os.path.relpath(os.path.join(base, name), root))
    return files


def read_lines(root, path):
    with open(os.path.join(root, path), encoding="utf-8") as f:
        return f.read().split("\n")


def long_files(root, files):
    for path in files:
        count = len(read_lines(root, path)) - 1
        if count > MAX_FILE_LINES:
            yield f"{path}: {count} lines (at most {MAX_FILE_LINES})"


def has_reason(lines, first):
    """Whether the comment block above line `first` (0-based) has the reason line."""
    i = first - 1
    # A template header or attribute line may stand between the comment and the name.
    while i >= 0 and lines[i].strip().startswith(("template", "[[")):
        i -= 1
    while i >= 0 and lines[i].strip().startswith("//"):
        if lines[i].strip()[2:].strip().startswith(REASON):
            return True
        i -= 1
    return False


def long_functions(root, files):
    ctags = shutil.which("ctags")
    if ctags is None:
        raise MissingTool("universal-ctags is missing (scripts/install_deps.sh installs it)")
    command = [ctags, "-x", "--_xformat=%{input}\t%{line}\t%{end}\t%{name}",
               "--kinds-c++=f", "--language-force=c++"] + files
    listing = subprocess.run(command, cwd=root, capture_output=True, text=True, check=True)
    cache = {}
    for row in listing.stdout.splitlines():
        path, first, last, name = row.split("\t")
        if not last:
            continue
        first, last = int(first), int(last)
        if last - first + 1 <= MAX_FUNCTION_LINES:
            continue
        lines = cache.setdefault(path, read_lines(root, path))
        if not has_reason(lines, first - 1):
            yield (f"{path}:{first}: {name} is {last - first + 1} lines (at most "
                   f"{MAX_FUNCTION_LINES} without a '// {REASON} ...' comment above it)")


def unit_of(path):
    return os.path.splitext(path)[0]


def include_breaches(root, files, layers):
    order = {layer: i for i, layer in enumerate(layers)}
    graph = {}
    known = {unit_of(p) for p in files}
    for path in files:
        folder = path.split(os.sep)[0]
        for number, line in enumerate(read_lines(root, path), 1):
            match = INCLUDE.match(line)
            if not match:
                continue
            target = match.group(1)
            target_folder = target.split("/")[0]
            if (folder in order and target_folder in order
                    and order[target_folder] > order[folder]):
                yield (f"{path}:{number}: includes {target}, a layer above {folder}/ "
                       f"(ATTEND_LAYERS)")
            if unit_of(target) in known and unit_of(target) != unit_of(path):
                graph.setdefault(unit_of(path), set()).add(unit_of(target))
    # A header without a .cc of its own (param_block_yaml.h, tracker_mode.h) holds declarations
    # that one unit's files share; a cycle through it alone is that unit's inside.
    implemented = {unit_of(p) for p in files if p.endswith(".cc")}
    for component in cycles(graph):
        if len([unit for unit in component if unit in implemented]) > 1:
            yield "include cycle between the units " + ", ".join(component)


def cycles(graph):
    """Each strongly connected set of two or more units (Tarjan's algorithm, iterative)."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []
    counter = [0]
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph.get(start, ()))))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter[0]
                    counter[0] += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    found.append(sorted(component))
    return sorted(found)


def option_reads(root, files):
    for path in files:
        if path.startswith("config" + os.sep):
            continue
        for number, line in enumerate(read_lines(root, path), 1):
            code = line.split("//")[0]
            match = OPTION_CALL.search(code)
            if match:
                yield (f"{path}:{number}: {match.group(1)} outside config/ (read options "
                       f"through a field table)")


def main(argv):
    root = os.path.abspath(argv[1] if len(argv) > 1 else
                           os.path.join(os.path.dirname(__file__), ".."))
    try:
        layers = read_layers(root)
        files = library_files(root, layers + ["python"])
        breaches = (list(long_files(root, files)) + list(long_functions(root, files))
                    + list(include_breaches(root, files, layers))
                    + list(option_reads(root, files)))
    except MissingTool as error:
        print(f"check_structure: skipped: {error}", file=sys.stderr)
        return 77
    except (OSError, RuntimeError, subprocess.CalledProcessError) as error:
        print(f"check_structure: {error}", file=sys.stderr)
        return 2
    for breach in breaches:
        print(breach)
    print(f"check_structure: {len(files)} library files, {len(breaches)} breaches")
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
