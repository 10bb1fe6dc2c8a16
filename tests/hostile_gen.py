#!/usr/bin/env python3
"""Writes the hostile meshes of tests/cli_hostile.sh (issue 20, item 6).

usage: hostile_gen.py CASE OUT [N]
Each mesh is plain text (OBJ/OFF/PLY) or binary PLY, written fast enough that
the 2M-face grid takes a few seconds. Only the standard library is used.
"""
import math
import struct
import sys


def grid(n, m=None, bump=0.3, scale=1.0, offset=(0.0, 0.0, 0.0)):
    """A bumpy (n x m)-quad height field over the unit square: 2*n*m triangles."""
    m = m or n
    vs = []
    for j in range(m + 1):
        for i in range(n + 1):
            x, y = i / n, j / m
            z = bump * math.sin(3.0 * x) * math.cos(2.0 * y)
            vs.append(((x + offset[0]) * scale, (y + offset[1]) * scale, (z + offset[2]) * scale))
    fs = []
    for j in range(m):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            fs.append((a, b, c))
            fs.append((a, c, d))
    return vs, fs


def sphere(nu=24, nv=12, scale=1.0):
    """A closed UV sphere (poles are single vertices)."""
    vs = [(0.0, 0.0, scale)]
    for j in range(1, nv):
        t = math.pi * j / nv
        for i in range(nu):
            p = 2 * math.pi * i / nu
            vs.append((scale * math.sin(t) * math.cos(p), scale * math.sin(t) * math.sin(p), scale * math.cos(t)))
    vs.append((0.0, 0.0, -scale))
    south = len(vs) - 1
    ring = lambda j, i: 1 + (j - 1) * nu + (i % nu)
    fs = []
    for i in range(nu):
        fs.append((0, ring(1, i), ring(1, i + 1)))
    for j in range(1, nv - 1):
        for i in range(nu):
            a, b = ring(j, i), ring(j, i + 1)
            c, d = ring(j + 1, i + 1), ring(j + 1, i)
            fs.append((a, d, c))
            fs.append((a, c, b))
    for i in range(nu):
        fs.append((south, ring(nv - 1, i + 1), ring(nv - 1, i)))
    return vs, fs


def cone(n, apex, rim_z, r=1.0):
    """An open cone: a fan of n triangles around its apex (vertex 0)."""
    vs = [apex] + [(r * math.cos(2 * math.pi * i / n), r * math.sin(2 * math.pi * i / n), rim_z) for i in range(n)]
    fs = [(0, 1 + i, 1 + (i + 1) % n) for i in range(n)]
    return vs, fs


def write_obj(path, vs, fs, extra_lines=()):
    with open(path, "w") as f:
        f.write("".join("v %.17g %.17g %.17g\n" % v for v in vs))
        f.write("".join("f " + " ".join(str(i + 1) for i in t) + "\n" for t in fs))
        for line in extra_lines:
            f.write(line + "\n")


def write_off(path, vs, fs):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(vs), len(fs)))
        f.write("".join("%r %r %r\n" % v for v in vs))
        f.write("".join("%d %s\n" % (len(t), " ".join(map(str, t))) for t in fs))


def write_ply_binary(path, vs, fs):
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (len(vs), len(fs))).encode())
        f.write(b"".join(struct.pack("<3f", *v) for v in vs))
        f.write(b"".join(struct.pack("<B3i", 3, *t) for t in fs))


def main():
    case, out = sys.argv[1], sys.argv[2]
    n = int(sys.argv[3]) if len(sys.argv) > 3 else 0
    if case == "nonmanifold_edge":
        # A bumpy grid with two fins on one interior edge: that edge has 4 faces.
        vs, fs = grid(12)
        a, b = fs[100][0], fs[100][2]
        pa, pb = vs[a], vs[b]
        mid = ((pa[0] + pb[0]) / 2, (pa[1] + pb[1]) / 2)
        vs.append((mid[0], mid[1], 0.5))
        vs.append((mid[0], mid[1], -0.5))
        fs.append((a, b, len(vs) - 2))
        fs.append((b, a, len(vs) - 1))
        write_obj(out, vs, fs)
    elif case == "nonmanifold_vertex":
        # Two open cones whose apexes are the same vertex (an hourglass).
        v1, f1 = cone(16, (0.0, 0.0, 0.0), 1.0)
        v2, f2 = cone(16, (0.0, 0.0, 0.0), -1.0)
        vs = v1 + v2[1:]
        off = len(v1) - 1
        fs = f1 + [tuple(0 if i == 0 else i + off for i in t) for t in f2]
        write_obj(out, vs, fs)
    elif case == "zero_area":
        # A grid with zero-area faces: a sliver on three collinear vertices,
        # a face with two coincident vertices, and a face on one point.
        vs, fs = grid(10)
        base = len(vs)
        vs += [(0.2, 0.2, 2.0), (0.4, 0.4, 2.0), (0.6, 0.6, 2.0)]   # collinear
        vs += [(0.5, 0.5, 3.0), (0.5, 0.5, 3.0), (0.7, 0.5, 3.0)]   # two coincident
        vs += [(0.1, 0.1, 4.0)] * 3                                 # one point
        fs += [(base, base + 1, base + 2), (base + 3, base + 4, base + 5), (base + 6, base + 7, base + 8)]
        # and zero-area faces glued into the grid's own vertices (collinear along a row)
        fs += [(0, 1, 2), (3, 4, 5)]
        write_obj(out, vs, fs)
    elif case == "duplicate":
        # Every tenth face of a grid repeated, half of them with reversed orientation.
        vs, fs = grid(12)
        extra = []
        for k, t in enumerate(fs[::10]):
            extra.append(t if k % 2 == 0 else (t[0], t[2], t[1]))
        write_obj(out, vs, fs + extra)
    elif case == "isolated":
        # A grid plus 500 vertices no face uses, some far away.
        vs, fs = grid(12)
        vs += [(100.0 * math.sin(k), 50.0 * math.cos(k), k * 1.0) for k in range(500)]
        write_obj(out, vs, fs)
    elif case == "components":
        # n tiny disconnected tetrahedra (closed: each needs a cut) on a lattice.
        n = n or 1000
        vs, fs = [], []
        side = int(math.ceil(n ** (1.0 / 3.0)))
        for k in range(n):
            x, y, z = k % side, (k // side) % side, k // (side * side)
            s = 0.01 * (1 + (k % 7) * 0.1)
            b = len(vs)
            vs += [(x, y, z), (x + s, y, z), (x, y + s, z), (x, y, z + s)]
            fs += [(b, b + 2, b + 1), (b, b + 1, b + 3), (b, b + 3, b + 2), (b + 1, b + 2, b + 3)]
        write_obj(out, vs, fs)
    elif case == "huge_coords":
        vs, fs = sphere(scale=1e30)
        write_obj(out, vs, fs)
    elif case == "tiny_coords":
        vs, fs = sphere(scale=1e-30)
        write_obj(out, vs, fs)
    elif case == "huge_offset":
        # A small grid far from the origin: its extent is lost against the offset in float.
        vs, fs = grid(10, offset=(1e8, 1e8, 1e8))
        write_obj(out, vs, fs)
    elif case == "nan":
        vs, fs = grid(6)
        vs[10] = (float("nan"), 0.0, 0.0)
        write_obj(out, vs, fs)
    elif case == "inf":
        vs, fs = grid(6)
        vs[10] = (0.0, float("inf"), 0.0)
        write_off(out, vs, fs)
    elif case == "nan_binary":
        vs, fs = grid(6)
        vs[3] = (0.0, 0.0, float("nan"))
        write_ply_binary(out, vs, fs)
    elif case == "single":
        write_obj(out, [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], [(0, 1, 2)])
    elif case == "degenerate_polygons":
        # Polygons with repeated indices and collinear corners, next to a sane grid.
        vs, fs = grid(8)
        b = len(vs)
        vs += [(2.0, 0.0, 0.0), (3.0, 0.0, 0.0), (4.0, 0.0, 0.0), (3.0, 1.0, 0.0), (5.0, 0.0, 0.0)]
        lines = [
            "f %d %d %d" % (b + 1, b + 1, b + 1),                   # one vertex thrice
            "f %d %d %d %d" % (b + 1, b + 2, b + 2, b + 4),         # quad with a repeated corner
            "f %d %d %d" % (b + 1, b + 2, b + 3),                   # three collinear points
            "f %d %d %d %d" % (b + 1, b + 2, b + 3, b + 5),         # collinear quad
            "f %d %d %d %d %d" % (b + 1, b + 2, b + 4, b + 2, b + 3),  # pentagon revisiting a corner
        ]
        write_obj(out, vs, fs, lines)
    elif case == "only_degenerate":
        # Nothing but zero-area faces: there is no surface to unwrap.
        write_obj(out, [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (2.0, 0.0, 0.0), (3.0, 0.0, 0.0)],
                  [(0, 1, 2), (1, 2, 3), (0, 0, 3)])
    elif case == "large":
        # A bumpy grid of about n faces, binary PLY (fast to write and to read).
        n = n or 200000
        k = max(2, int(math.sqrt(n / 2.0)))
        vs, fs = grid(k, bump=0.1)
        write_ply_binary(out, vs, fs)
    else:
        sys.exit("unknown case " + case)


if __name__ == "__main__":
    main()
