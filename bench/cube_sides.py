#!/usr/bin/env python3
"""Issue 20, item 5: does PatchNet find a cube's six sides?

    python3 bench/cube_sides.py NEUV [N] [SEEDS] [--box A,B,C] [--turn]
                                [-- extra segment options]

Writes a cube of N x N quads per side (two triangles each, the diagonal
in each side's own coordinates; default N = 12: 1728 faces), runs
`neuv segment CUBE --charts 6 --seed S` for S = 1..SEEDS (default 10) and
says, per seed, how many charts came out and whether each is one whole side
(all its faces share one normal and there are six of them, 2 N^2 faces each).
--box A,B,C stretches the cube into a box of those side lengths (still N x N
quads per side); --turn turns it by a fixed rotation that aligns no side
with an axis. Last line: "sides found for K of SEEDS seeds"."""
import collections, json, os, subprocess, sys, tempfile


def turned(p):
    """p turned by a fixed rotation (about (1, 2, 3) by 0.7 rad)."""
    import math
    k = [1 / math.sqrt(14), 2 / math.sqrt(14), 3 / math.sqrt(14)]
    c, s = math.cos(0.7), math.sin(0.7)
    d = sum(k[i] * p[i] for i in range(3))
    x = [k[1] * p[2] - k[2] * p[1], k[2] * p[0] - k[0] * p[2], k[0] * p[1] - k[1] * p[0]]
    return tuple(p[i] * c + x[i] * s + k[i] * d * (1 - c) for i in range(3))


def write_cube(path, n, box=(1, 1, 1), turn=False):
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
            q = tuple((x / n - 0.5) * box[i] for i, x in enumerate(p))
            f.write("v %.17g %.17g %.17g\n" % (turned(q) if turn else q))
        for t in faces:
            f.write("f %d %d %d\n" % tuple(x + 1 for x in t))


def sides(obj, n):
    """Charts of a `neuv segment` OBJ (its groups) and whether each is one side:
    six charts of 2 N^2 faces each, every face of a chart with its first
    face's normal (to 1e-6) and the six normals apart."""
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
        m = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        l = sum(x * x for x in m) ** 0.5
        return [x / l for x in m]
    firsts, ok = [], len(chart_faces) == 6
    for fs in chart_faces.values():
        n0 = normal(fs[0])
        firsts.append(n0)
        ok = ok and len(fs) == 2 * n * n and all(sum(a * b for a, b in zip(n0, normal(t))) > 1 - 1e-6 for t in fs)
    ok = ok and all(sum(a * b for a, b in zip(p, q)) < 0.5 for i, p in enumerate(firsts) for q in firsts[:i])
    return len(chart_faces), ok


def main():
    args = sys.argv[1:]
    extra = args[args.index("--") + 1:] if "--" in args else []
    args = args[:args.index("--")] if "--" in args else args
    box, turn = (1, 1, 1), "--turn" in args
    if "--box" in args:
        i = args.index("--box")
        box = tuple(float(x) for x in args[i + 1].split(","))
        del args[i:i + 2]
    args = [a for a in args if a != "--turn"]
    neuv = args[0]
    n = int(args[1]) if len(args) > 1 else 12
    seeds = int(args[2]) if len(args) > 2 else 10
    tmp = tempfile.mkdtemp(prefix="cube_sides-")
    cube = os.path.join(tmp, "cube%d.obj" % n)
    write_cube(cube, n, box, turn)
    found = 0
    for s in range(1, seeds + 1):
        out = os.path.join(tmp, "seg%d.obj" % s)
        r = subprocess.run([neuv, "segment", cube, "-o", out, "--charts", "6", "--seed", str(s), "--json"] + extra,
                           capture_output=True, text=True, check=True)
        rep = json.loads(r.stdout)
        count, ok = sides(out, n)
        found += ok
        print("seed %d: %d charts, %s; loss_cos %.4f, loss_geo %.4f, %d iterations, %d re-seeded"
              % (s, count, "six sides" if ok else "not the sides", rep["loss_cos"], rep["loss_geo"], rep["iterations"],
                 rep.get("reseeds", 0)))
    print("sides found for %d of %d seeds" % (found, seeds))


if __name__ == "__main__":
    main()
