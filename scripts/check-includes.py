#!/usr/bin/env python3
"""Checks the include graph of the project's own files (scripts/test.sh runs it before the tests).

  - Layers: sim/ includes only sim/; io/ only sim/ and io/; widgets/ only sim/ and widgets/; app/
    anything. Nothing in sim/ or io/ includes a Qt header. (DESIGN.md: sim -> io | widgets -> app.)
  - No cycle: no file reaches itself through the project's includes (quoted, from the root).

Prints what it found and exits 1 on any finding; `scripts/check-includes.py --graph` also prints the
number of files and edges.
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FOLDERS = ["sim", "io", "widgets", "app"]
ALLOWED = {  # a folder's files may include project files from these folders
    "sim": {"sim"},
    "io": {"sim", "io"},
    "widgets": {"sim", "widgets"},
    "app": {"sim", "io", "widgets", "app"},
}
NO_QT = {"sim", "io"}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def project_files():
    for folder in FOLDERS:
        for dirpath, _, names in os.walk(os.path.join(ROOT, folder)):
            for name in sorted(names):
                if name.endswith((".h", ".cpp")):
                    yield os.path.relpath(os.path.join(dirpath, name), ROOT)


def main():
    files = sorted(project_files())
    known = set(files)
    edges = {}
    problems = []
    for path in files:
        layer = path.split(os.sep)[0]
        targets = []
        with open(os.path.join(ROOT, path), encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                kind, name = m.groups()
                if kind == "<":
                    if layer in NO_QT and re.match(r"Q[A-Za-z]", name):
                        problems.append(f"{path}:{number}: {layer}/ includes the Qt header <{name}>")
                    continue
                top = name.split("/")[0]
                if top in ALLOWED and top not in ALLOWED[layer]:
                    problems.append(f"{path}:{number}: {layer}/ includes {name} (upward: {layer}/ may include "
                                    f"{', '.join(sorted(ALLOWED[layer]))}/ only)")
                if name in known:
                    targets.append(name)
        edges[path] = targets

    # Cycles: depth-first search, colouring files on the current path.
    state = {}
    stack = []

    def visit(node):
        state[node] = 1
        stack.append(node)
        for nxt in edges.get(node, []):
            if state.get(nxt) == 1:
                cycle = stack[stack.index(nxt):] + [nxt]
                problems.append("include cycle: " + " -> ".join(cycle))
            elif nxt not in state:
                visit(nxt)
        stack.pop()
        state[node] = 2

    sys.setrecursionlimit(10000)
    for path in files:
        if path not in state:
            visit(path)

    if "--graph" in sys.argv:
        print(f"{len(files)} files, {sum(len(t) for t in edges.values())} project includes")
    if problems:
        print("!! the include graph breaks the layering:")
        for p in problems:
            print("   " + p)
        return 1
    print(f"== includes: {len(files)} files in {', '.join(FOLDERS)}: no cycle, nothing upward, no Qt in sim/ or io/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
