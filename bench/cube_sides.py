#!/usr/bin/env python3
"""Issue 20, item 5: does PatchNet find a cube's six sides?

    python3 bench/cube_sides.py NEUV [N] [SEEDS] [-- extra segment options]

Writes a cube of N x N quads per side (two triangles each, the diagonal
in each side's own coordinates; default N = 12: 1728 faces), runs
`neuv segment CUBE --charts 6 --seed S` for S = 1..SEEDS (default 10) and
says, per seed, how many charts came out and whether each is one whole side
(all its faces share one normal and there are six of them, 2 N^2 faces each).
Last line: "sides found for K of SEEDS seeds"."""
import collections, json, os, subprocess, sys, tempfile


def write_cube(path, n):
    index, verts, faces = {}, [], []

    def vid(p):
        if p not in index:
            index[p] = len(verts)
            verts.append(p)
        return index[p]

    for axis in range(3):
        for side in (0, n):
            for i in range(n):
                for j in range(n):
                    def at(a, b):
                        p = [0, 0, 0]
                        p[axis], p[(axis + 1) % 3], p[(axis + 2) % 3] = side, a, b
                        return tuple(p)
                    q = [vid(at(i, j)), vid(at(i + 1, j)), vid(at(i + 1, j + 1)), vid(at(i, j + 1))]
                    if side == 0:
                        q.reverse()  # outward on both sides
                    faces += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
    with open(path, "w") as f:
        for p in verts:
            f.write("v %.17g %.17g %.17g\n" % tuple(x / n - 0.5 for x in p))
        for t in faces:
            f.write("f %d %d %d\n" % tuple(x + 1 for x in t))


def sides(obj):
    """Charts of a `neuv segment` OBJ (its groups) and whether each is one side."""
    v, chart_faces, group = [], collections.defaultdict(list), None
    for line in open(obj):
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            v.append(tuple(map(float, w[1:4])))
        elif w[0] == "g":
            group = w[1]
        elif w[0] == "f":
            chart_faces[group].append([int(x.split("/")[0]) - 1 for x in w[1:4]])
    def normal(t):
        a, b, c = (v[i] for i in t)
        u = [b[k] - a[k] for k in range(3)]
        w = [c[k] - a[k] for k in range(3)]
        n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        k = max(range(3), key=lambda k: abs(n[k]))
        return k, n[k] > 0
    kinds = [collections.Counter(normal(t) for t in fs) for fs in chart_faces.values()]
    return len(kinds), len(kinds) == 6 and all(len(c) == 1 for c in kinds) and len({next(iter(c)) for c in kinds}) == 6


def main():
    args = sys.argv[1:]
    extra = args[args.index("--") + 1:] if "--" in args else []
    args = args[:args.index("--")] if "--" in args else args
    neuv = args[0]
    n = int(args[1]) if len(args) > 1 else 12
    seeds = int(args[2]) if len(args) > 2 else 10
    tmp = tempfile.mkdtemp(prefix="cube_sides-")
    cube = os.path.join(tmp, "cube%d.obj" % n)
    write_cube(cube, n)
    found = 0
    for s in range(1, seeds + 1):
        out = os.path.join(tmp, "seg%d.obj" % s)
        r = subprocess.run([neuv, "segment", cube, "-o", out, "--charts", "6", "--seed", str(s), "--json"] + extra,
                           capture_output=True, text=True, check=True)
        rep = json.loads(r.stdout)
        count, ok = sides(out)
        found += ok
        print("seed %d: %d charts, %s; loss_cos %.4f, loss_geo %.4f, %d iterations"
              % (s, count, "six sides" if ok else "not the sides", rep["loss_cos"], rep["loss_geo"], rep["iterations"]))
    print("sides found for %d of %d seeds" % (found, seeds))


if __name__ == "__main__":
    main()
