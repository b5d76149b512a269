#!/usr/bin/env python3
"""The shape of src/: which folder may include which, no include cycle between units, and how big things are.

    tools/check_structure.py [SRC]              check the layers and cycles (exit 1 on a violation)
    tools/check_structure.py --report [SRC]     also print lines per folder, the largest files
    tools/check_structure.py --functions BUILD  functions over 80 lines (clang-tidy's readability-function-size
                                                over BUILD/compile_commands.json; needs clang-tidy)

A unit is a header and its source file together (world/arena.hpp and world/arena.cpp). Unit A depends on unit
B when a file of A includes a header of B ("B.hpp"). Folders are layers (docs/architecture.md); LAYERS lists
what each may include, and an include outside it is a violation, as is a cycle of units (Tarjan's strongly
connected components), an include of a file outside src/ (the library knows no executable), or a folder
holding more than LARGEST_SHARE of src/'s lines (a folder's own files; world/ and world/map/ count apart).
"""
import argparse
import collections
import json
import os
import re
import subprocess
import sys

# What each folder of src/ may include besides itself: the one-way picture of docs/architecture.md. world/ is
# itself layered: map/ (maps and meshes in), field/ (the static distance field) and bodies/ (movers and bodies
# in time) under world/ (the Arena over them), under collision/ (each run's collision world).
WORLD_MAP = {"core", "geometry"}
WORLD_FIELD = WORLD_MAP | {"world/map"}
WORLD_BODIES = WORLD_MAP | {"world/map"}
WORLD = WORLD_MAP | {"world/map", "world/field", "world/bodies"}
WORLD_ALL = WORLD | {"world", "world/collision"}
LAYERS = {
    "core": set(),
    "geometry": {"core"},
    "fuzzy": {"core"},
    "world/map": WORLD_MAP,
    "world/field": WORLD_FIELD,
    "world/bodies": WORLD_BODIES,
    "world": WORLD,
    "world/collision": WORLD | {"world"},
    "sense": {"core", "geometry"} | WORLD_ALL,
    "game": {"core", "geometry", "fuzzy", "sense"} | WORLD_ALL,
    "players": {"core", "geometry", "fuzzy", "sense", "game"} | WORLD_ALL,
    "sweep": {"core"},
    "results": {"core", "geometry", "fuzzy", "game", "players", "sense"} | WORLD_ALL,
    "regress": {"core", "geometry", "fuzzy", "game", "players", "results", "sense"} | WORLD_ALL,
    "experiment": {"core", "geometry", "fuzzy", "game", "players", "sweep", "results", "sense"} | WORLD_ALL,
    "view": {"core", "geometry", "fuzzy", "game", "sense"} | WORLD_ALL,
    "env": {"core", "geometry", "fuzzy", "game", "players", "sense"} | WORLD_ALL,
}
# No folder may hold more than this share of src/'s lines: a folder that large is several concepts.
LARGEST_SHARE = 0.20
SOURCE_EXTENSIONS = (".cpp", ".hpp", ".hpp.in")
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.MULTILINE)
FUNCTION_LIMIT = 80


def folder_of(path):
    """The folder of a file under src/: "world/map" for world/map/map_spec.hpp, "game" for game/sim.hpp."""
    return path.rsplit("/", 1)[0] if "/" in path else ""


def folder_lines(files):
    """Lines per folder (a folder's own files, not its sub-folders'), largest first."""
    per_folder = collections.Counter()
    for path, text in files.items():
        per_folder[folder_of(path)] += text.count("\n")
    return dict(per_folder.most_common())


def unit_of(path):
    for ext in SOURCE_EXTENSIONS:
        if path.endswith(ext):
            return path[: -len(ext)]
    return path


def read_tree(src):
    """{relative path: text} of every C++ file under src."""
    files = {}
    for root, _, names in os.walk(src):
        for name in names:
            if name.endswith(SOURCE_EXTENSIONS):
                full = os.path.join(root, name)
                with open(full, encoding="utf-8") as f:
                    files[os.path.relpath(full, src).replace(os.sep, "/")] = f.read()
    return files


def strongly_connected(graph):
    """Tarjan's algorithm, iterative: the components of more than one node (or a node that reaches itself)."""
    index, low, on_stack, stack, components = {}, {}, set(), [], []
    counter = 0
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, edges = work[-1]
            advanced = False
            for nxt in edges:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter
                    counter += 1
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(sorted(graph.get(nxt, ())))))
                    advanced = True
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
            if advanced:
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
                if len(component) > 1 or node in graph.get(node, ()):
                    components.append(sorted(component))
    return components


def check_layers(src):
    files = read_tree(src)
    headers = {path for path in files if path.endswith((".hpp", ".hpp.in"))}
    generated = {path[: -len(".in")].split("/")[-1] for path in files if path.endswith(".hpp.in")}
    problems = []
    graph = collections.defaultdict(set)
    for path, text in sorted(files.items()):
        folder = folder_of(path)
        if folder not in LAYERS:
            problems.append(f"{path}: folder '{folder}' is not a layer of tools/check_structure.py")
            continue
        unit = unit_of(path)
        graph[unit]
        for included in INCLUDE.findall(text):
            if included in generated:
                continue  # a header CMake writes from a .hpp.in of the same folder
            if included not in headers:
                problems.append(f"{path}: includes \"{included}\", which is not a header of src/")
                continue
            target_folder = folder_of(included)
            if target_folder != folder and target_folder not in LAYERS[folder]:
                problems.append(f"{path}: includes \"{included}\": {folder}/ may not depend on {target_folder}/")
            target = unit_of(included)
            if target != unit:
                graph[unit].add(target)
    for component in strongly_connected(graph):
        problems.append("include cycle between units: " + " -> ".join(component + component[:1]))
    total = sum(text.count("\n") for text in files.values())
    for folder, n in folder_lines(files).items():
        if n > LARGEST_SHARE * total:
            problems.append(f"{folder}/ holds {n} of src/'s {total} lines, over {LARGEST_SHARE:.0%}: split it by concept")
    return files, problems


def report(src, files):
    lines = {path: text.count("\n") for path, text in files.items()}
    total = sum(lines.values())
    print(f"{total} lines in {len(files)} files under {src}")
    for folder, n in folder_lines(files).items():
        print(f"  {folder + '/':<17} {n:>6}  {100.0 * n / total:5.1f} %")
    print("largest files:")
    for path, n in sorted(lines.items(), key=lambda kv: -kv[1])[:10]:
        print(f"  {n:>6}  {path}")


def long_functions(build, src):
    """Functions of src/ over FUNCTION_LIMIT lines, by clang-tidy over the build's compilation database."""
    with open(os.path.join(build, "compile_commands.json"), encoding="utf-8") as f:
        sources = sorted({e["file"] for e in json.load(f) if os.path.realpath(e["file"]).startswith(os.path.realpath(src) + os.sep)})
    config = "{CheckOptions: [{key: readability-function-size.LineThreshold, value: %d}]}" % FUNCTION_LIMIT
    found = []
    jobs = max(1, os.cpu_count() or 1)
    procs = []
    for i in range(0, len(sources), 1):
        procs.append(subprocess.Popen(["clang-tidy", "-p", build, "--quiet", "--checks=-*,readability-function-size",
                                       f"--config={config}", sources[i]],
                                      stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True))
        if len(procs) >= jobs:
            found += parse_tidy(procs.pop(0).communicate()[0])
    for p in procs:
        found += parse_tidy(p.communicate()[0])
    return sorted(set(found))


def parse_tidy(output):
    out, pending = [], None
    for line in output.splitlines():
        m = re.match(r"(.+?):(\d+):\d+: warning: function '([^']+)' exceeds", line)
        if m:
            pending = (m.group(1), int(m.group(2)), m.group(3))
            continue
        m = re.search(r"note: (\d+) lines including", line)
        if m and pending:
            out.append((pending[0], pending[1], pending[2], int(m.group(1))))
            pending = None
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("src", nargs="?", default=os.path.join(os.path.dirname(__file__), "..", "src"))
    parser.add_argument("--report", action="store_true", help="print lines per folder and the largest files")
    parser.add_argument("--functions", metavar="BUILD", help="list functions over 80 lines (clang-tidy)")
    args = parser.parse_args()
    src = os.path.normpath(args.src)
    files, problems = check_layers(src)
    if args.report:
        report(src, files)
    if args.functions:
        long = long_functions(args.functions, src)
        print(f"functions over {FUNCTION_LIMIT} lines: {len(long)}")
        for file, line, name, n in long:
            print(f"  {n:>4}  {os.path.relpath(file, src)}:{line}  {name}")
    for p in problems:
        print("error:", p, file=sys.stderr)
    if not problems:
        print(f"layers: {len(files)} files, every include points down the layers, no include cycle between units")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
