#!/usr/bin/env python3
"""Checks the crate's module graph from its source: no file imports the crate root (lib.rs),
no module imports one of a higher layer (docs/architecture.md), no two files import each other
(no cycle), no file inside a domain imports through its domain's facade (`mod.rs` that only
re-exports). Exits 1 and lists what it found. Files are cut by concept, not by length (a type and
its inherent impls in one file, or in a folder named for it: docs/architecture.md); the longest
are printed.

Imports are read from `crate::…` and `super::…` paths outside comments and strings; a path is
attributed to the longest module (file) prefix it names.
"""
import glob
import os
import re
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src")
LAYERS = {
    "error": 0, "guard": 1, "schedule": 1, "lifecycle": 1, "portable": 1, "spectrum": 2, "wind": 3, "lod": 4,
    "freefall": 5, "cloth": 5, "aero": 6, "render": 7, "inspector": 8, "plugins": 9,
}
FACADES = {("aero",), ("cloth",), ("freefall",), ("wind",), ("spectrum",)}


def module_of(path):
    parts = os.path.relpath(path, ROOT)[:-3].split(os.sep)
    if parts[-1] in ("mod", "lib"):
        parts = parts[:-1]
    return tuple(parts)


def code_of(text):
    """The text without comments, strings and `#[cfg(test)] mod tests`."""
    cut = text.find("#[cfg(test)]\nmod tests")
    if cut >= 0:
        text = text[:cut]
    lines = [line for line in text.split("\n") if not line.strip().startswith("//")]
    return re.sub(r'"(\\.|[^"\\])*"', '""', "\n".join(lines), flags=re.S)


def main():
    files = sorted(glob.glob(os.path.join(ROOT, "**", "*.rs"), recursive=True))
    modules = {module_of(f): f for f in files}

    def resolve(parts):
        for k in range(len(parts), -1, -1):
            if tuple(parts[:k]) in modules:
                return tuple(parts[:k])
        return ()

    problems = []
    sizes = []
    edges = {}
    for module, path in modules.items():
        text = open(path).read()
        sizes.append((text.count("\n"), os.path.relpath(path, ROOT)))
        code = code_of(text)
        deps = set()
        for m in re.finditer(r"(?<!::)(?<!\bin )\b(crate|super)((?:::super)*)((?:::\w+)+|::\{)", code):
            kind, supers, rest = m.group(1), m.group(2), m.group(3)
            if rest == "::{":
                inner = code[m.end():code.index("}", m.end())]
                paths = [[n.strip().split("::")[0]] for n in inner.split(",") if n.strip()]
            else:
                paths = [rest.split("::")[1:]]
            if kind == "crate":
                base = []
            else:
                up = 1 + supers.count("super")
                base = list(module[: max(len(module) - up, 0)])
            for p in paths:
                target = resolve(base + [x for x in p if x != "self"])
                if target != module:
                    deps.add(target)
        edges[module] = deps
    for module, deps in sorted(edges.items()):
        name = "/".join(module) or "lib"
        for target in sorted(deps):
            if module and target == ():
                problems.append(f"{name} imports the crate root")
            elif module and target and target[0] != module[0]:
                if LAYERS.get(target[0], 99) >= LAYERS.get(module[0], 99):
                    problems.append(f"{name} imports {'/'.join(target)}, a layer not below it")
            elif target in FACADES and len(module) > len(target) and module[: len(target)] == target:
                problems.append(f"{name} imports through the facade {'/'.join(target)}")
    # Cycles between files (Tarjan's strongly connected components).
    index, low, stack, on, counter, cycles = {}, {}, [], set(), [0], []

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                cycles.append(component)

    sys.setrecursionlimit(10000)
    for v in edges:
        if v not in index:
            visit(v)
    for c in cycles:
        problems.append("files import each other: " + ", ".join("/".join(m) for m in c))
    count = sum(len(d) for d in edges.values())
    print(f"module graph: {len(modules)} files, {count} imports between them")
    for p in problems:
        print("  " + p)
    if problems:
        sys.exit(1)
    print("  no import up to lib.rs or a higher layer, no cycle")
    print("  longest files: " + ", ".join(f"{p} ({n})" for n, p in sorted(sizes, reverse=True)[:5]))


if __name__ == "__main__":
    main()
