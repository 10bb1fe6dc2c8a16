"""Procedural test meshes and OBJ reading and writing for the tests."""
import numpy as np


def torus(n=24, m=12, R=1.0, r=0.35, flip=False):
    """A bumpy torus, n by m quads split into two triangles each (along the
    other diagonal with flip: the same vertices triangulated differently)."""
    u = np.linspace(0, 2 * np.pi, n, endpoint=False)
    v = np.linspace(0, 2 * np.pi, m, endpoint=False)
    U, W = np.meshgrid(u, v, indexing="ij")
    rr = r * (1 + 0.1 * np.sin(3 * U) * np.cos(2 * W))
    V = np.stack([(R + rr * np.cos(W)) * np.cos(U), (R + rr * np.cos(W)) * np.sin(U), rr * np.sin(W)], -1)
    i, j = np.meshgrid(np.arange(n), np.arange(m), indexing="ij")
    a, b = i * m + j, (i + 1) % n * m + j
    c, d = (i + 1) % n * m + (j + 1) % m, i * m + (j + 1) % m
    if flip:
        F = np.stack([np.stack([a, b, d], -1), np.stack([b, c, d], -1)], 2)
    else:
        F = np.stack([np.stack([a, b, c], -1), np.stack([a, c, d], -1)], 2)
    return V.reshape(-1, 3), F.reshape(-1, 3)


def write_obj(path, V, F):
    """repr gives the shortest decimal that reads back as the same double,
    so the CLI reads exactly the arrays the Python calls get."""
    with open(path, "w") as f:
        for p in V:
            f.write("v %r %r %r\n" % tuple(float(x) for x in p))
        for t in F:
            f.write("f %d %d %d\n" % tuple(int(x) + 1 for x in t))


def read_obj(path):
    """Positions (N, 3), UVs (T, 2), and per face the vertex and UV indices
    (M, 3) each, of an OBJ with triangles written v/vt."""
    V, T, FV, FT = [], [], [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                V.append([float(x) for x in w[1:4]])
            elif w[0] == "vt":
                T.append([float(x) for x in w[1:3]])
            elif w[0] == "f":
                corners = [c.split("/") for c in w[1:]]
                assert len(corners) == 3, line
                FV.append([int(c[0]) - 1 for c in corners])
                FT.append([int(c[1]) - 1 for c in corners])
    return np.array(V), np.array(T), np.array(FV), np.array(FT)
