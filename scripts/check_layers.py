#!/usr/bin/env python3
"""Checks that the folders of src/ form layers.

usage: check_layers.py [--graph] [SRC]   (SRC: the src/ folder)

Reads every `#include "..."` in SRC (.c, .h, .cpp) and fails (exit 1, one line
per problem) on
  (a) a cycle between folders,
  (b) an include that goes against LEVEL below: a folder may include its own
      headers, the public header neuv/..., and headers of folders on a lower
      level; two folders on one level include each other only where
      SAME_LEVEL says so,
  (c) an include of a header that does not exist (under SRC, or under
      SRC/../include for neuv/...),
  (d) an include in src/cli of anything but neuv/... and cli/...: the
      command line is a program on the public API like any other.
A folder of SRC that LEVEL does not name is a problem too: a new folder must
take a place in the order. --graph prints the folder graph (include counts).
"""
import os
import re
import sys

# The layer order, lowest first. Data flows one way: input -> mesh cleaning ->
# geometry operators -> PatchNet (charts) -> parameterization networks ->
# repair -> packing -> export/report (docs: README.md "Layout").
LEVEL = {
    "core": 0,      # errors, logging, memory, JSON writer, atomic files, RNG, hashes, timers
    "mesh": 1,      # the triangle mesh, cleaning, topology, procedural shapes
    "nn": 1,        # tensors, reverse-mode ops, MLPs, Adam, checkpoints (knows no mesh)
    "io": 2,        # mesh readers and writers (OBJ/OFF/PLY/Assimp/glTF), PNG
    "spatial": 2,   # BVH and closest points on triangles
    "geometry": 2,  # sparse matrices, Laplacian, mass, eigenbasis, gradients, HKS, heat geodesics
    "charts": 2,    # face labels -> charts that are topological disks (split, merge, adjacency)
    "losses": 2,    # the PatchNet and parameterization losses, as nn ops
    "remesh": 3,    # simplify, subdivide, jitter, isotropic remeshing (CGAL)
    "atlas": 3,     # packing, splitting charts that pack badly, UV charts, previews
    "flatten": 3,   # one disk flattened: LSCM, harmonic, UV refinement
    "metrics": 4,   # UV metrics, overlap, a chart's injectivity check
    "compare": 4,   # UV consistency between two unwraps of one surface
    "models": 4,    # the networks only: DiffusionNet, PatchNet, parameterization networks
    "segment": 5,   # PatchNet's charts: argmax -> disks -> split/merge until each flattens
    "unwrap": 6,    # the pipeline, repairs, report, saved surface and category models
    "api": 7,       # the public API (include/neuv/neuv.h) on the layers below
    "cli": 8,       # the neuv command, one file per subcommand, on the public API
}
# (from, to) pairs of folders on one level that may include each other's headers.
SAME_LEVEL = set()
PUBLIC = "neuv"  # include/neuv/: the public API, allowed everywhere

INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
SOURCE_EXT = (".c", ".h", ".cpp")


def scan(src):
    """[(path relative to src, line number, included name)] of every quoted include."""
    out = []
    for root, dirs, files in os.walk(src):
        dirs.sort()
        for name in sorted(files):
            if not name.endswith(SOURCE_EXT):
                continue
            path = os.path.join(root, name)
            rel = os.path.relpath(path, src)
            with open(path, encoding="utf-8", errors="replace") as f:
                for n, line in enumerate(f, 1):
                    m = INCLUDE.match(line)
                    if m:
                        out.append((rel, n, m.group(1)))
    return out


def folder_of(rel):
    parts = rel.replace(os.sep, "/").split("/")
    return parts[0] if len(parts) > 1 else None


def cycles(graph):
    """Strongly connected components with more than one folder (Tarjan)."""
    index, low, on, stack, comps = {}, {}, set(), [], []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return comps


def main(argv):
    show_graph = "--graph" in argv
    args = [a for a in argv if not a.startswith("--")]
    if len(args) > 1 or any(a != "--graph" for a in argv if a.startswith("--")):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    src = os.path.abspath(args[0] if args else os.path.join(os.path.dirname(__file__), "..", "src"))
    include_dir = os.path.join(os.path.dirname(src), "include")
    if not os.path.isdir(src):
        print(f"check_layers: {src} is not a folder", file=sys.stderr)
        return 2

    problems = []
    for d in sorted(os.listdir(src)):
        if os.path.isdir(os.path.join(src, d)) and d not in LEVEL:
            problems.append(f"src/{d}/: folder not in the layer order (add it to LEVEL in {sys.argv[0]})")

    includes = scan(src)
    graph = {}      # folder -> {folder: [example "file:line"]}
    counts = {}     # (from, to) -> includes
    cli_private = []
    for rel, line, name in includes:
        where = f"src/{rel}:{line}"
        frm = folder_of(rel)
        # (c) the header exists
        if "/" in name:
            to = name.split("/")[0]
            base = include_dir if to == PUBLIC else src
            exists = os.path.isfile(os.path.join(base, name))
        else:
            to = frm
            exists = os.path.isfile(os.path.join(src, os.path.dirname(rel), name))
        if not exists:
            problems.append(f'{where}: #include "{name}": no such header')
        if frm is None or to == frm:
            continue
        if frm == "cli" and to not in (PUBLIC, "cli"):
            cli_private.append(f'{where}: #include "{name}"')
        if to == PUBLIC:
            continue
        counts[(frm, to)] = counts.get((frm, to), 0) + 1
        graph.setdefault(frm, {}).setdefault(to, []).append(where)
        # (b) downward only
        if to not in LEVEL:
            continue  # a missing header, or a folder the order lacks: both reported above
        if frm in LEVEL:
            lf, lt = LEVEL[frm], LEVEL[to]
            if lt > lf:
                problems.append(f'{where}: #include "{name}": {frm} (level {lf}) reaches up to {to} (level {lt})')
            elif lt == lf and (frm, to) not in SAME_LEVEL:
                problems.append(f'{where}: #include "{name}": {frm} and {to} share level {lf} and may not '
                                f'include each other')

    # (a) cycles between folders
    for comp in cycles({f: set(t) for f, t in graph.items()}):
        edges = [f"{f} -> {t} ({graph[f][t][0]})" for f in comp for t in sorted(graph.get(f, {})) if t in comp]
        problems.append("cycle between folders " + ", ".join(comp) + ": " + "; ".join(edges))

    # (d) the CLI through the public API only
    problems += [f"{c}: the CLI may include only neuv/... and cli/..." for c in cli_private]

    if show_graph:
        for frm in sorted(graph, key=lambda f: (LEVEL.get(f, 99), f)):
            tos = sorted(graph[frm], key=lambda t: (LEVEL.get(t, 99), t))
            print(f"{frm:9} -> " + ", ".join(f"{t} ({counts[(frm, t)]})" for t in tos))

    if problems:
        print(f"check_layers: {len(problems)} problem(s):")
        for p in problems:
            print("  " + p)
        return 1
    print(f"check_layers: {len(includes)} includes in src/, {len(graph)} folders include others: "
          f"no cycle, nothing upward or sideways, every header exists")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
