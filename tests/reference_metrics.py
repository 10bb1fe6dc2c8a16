#!/usr/bin/env python3
"""Reference implementation of the UV metrics of docs/metrics.md, in numpy.

Written from docs/metrics.md alone, separately from src/metrics/, so that
tests/cli_eval.sh can check that `neuv eval --json` and this script agree to
1e-6 relative on the same file. Where the page allows a choice of formula this
script deliberately takes a different one from the C code (the frame-free Gram
form of the singular values, other loop bounds for the raster).

usage: reference_metrics.py FILE.obj [--float32]
  --float32   round coordinates to float32 as they are read (to mirror a
              loader that stores what it reads in single precision)
Prints one JSON object: {"input", "vertices", "faces", "metrics": {...}}.
"""
import json
import math
import sys

import numpy as np

AREA_EPS = 1e-12
RASTER = 2048
UNIT_TOL = 1e-9


def read_obj(path, float32):
    """Positions (#V by 3), faces (#F by 3), UVs (#UV by 2), face UV indices (#F by 3)."""
    pos, uvs, tri, tri_uv = [], [], [], []
    with open(path) as fh:
        for line in fh:
            tok = line.split()
            if not tok:
                continue
            if tok[0] == "v":
                pos.append([float(x) for x in tok[1:4]])
            elif tok[0] == "vt":
                uvs.append([float(x) for x in tok[1:3]])
            elif tok[0] == "f":
                corners = []
                for t in tok[1:]:
                    parts = t.split("/")
                    if len(parts) < 2 or parts[1] == "":
                        sys.exit("no UVs: face corner '%s' has no texture index" % t)
                    vi, ti = int(parts[0]), int(parts[1])
                    vi = vi - 1 if vi > 0 else len(pos) + vi
                    ti = ti - 1 if ti > 0 else len(uvs) + ti
                    corners.append((vi, ti))
                if len(corners) != 3:
                    sys.exit("only triangles are supported by the reference")
                tri.append([c[0] for c in corners])
                tri_uv.append([c[1] for c in corners])
    dtype = np.float32 if float32 else np.float64
    pos = np.array(pos, dtype=dtype).astype(np.float64).reshape(-1, 3)
    uvs = np.array(uvs, dtype=dtype).astype(np.float64).reshape(-1, 2)
    return pos, np.array(tri, dtype=np.int64).reshape(-1, 3), uvs, np.array(tri_uv, dtype=np.int64).reshape(-1, 3)


def weld(pos, tri):
    """Vertices with identical positions become the first of them."""
    first = {}
    remap = np.empty(len(pos), dtype=np.int64)
    for i, p in enumerate(map(tuple, pos.tolist())):
        remap[i] = first.setdefault(p, i)
    return remap[tri]


def singular_values(e1, e2, d1, d2, area3, area_uv):
    """s1 >= s2 of J from the Gram matrices: tr(JᵀJ) = tr(Gq G3⁻¹), |det J| = |a|/A."""
    g11 = np.einsum("ij,ij->i", e1, e1)
    g12 = np.einsum("ij,ij->i", e1, e2)
    g22 = np.einsum("ij,ij->i", e2, e2)
    h11 = np.einsum("ij,ij->i", d1, d1)
    h12 = np.einsum("ij,ij->i", d1, d2)
    h22 = np.einsum("ij,ij->i", d2, d2)
    detg = (2 * area3) ** 2
    t = (h11 * g22 - 2 * h12 * g12 + h22 * g11) / detg
    d = np.abs(area_uv) / area3
    s1 = np.sqrt((t + np.sqrt(np.maximum(t * t - 4 * d * d, 0))) / 2)
    return s1, d / s1


class Forest:
    def __init__(self, n):
        self.parent = list(range(n))

    def find(self, x):
        root = x
        while self.parent[root] != root:
            root = self.parent[root]
        while self.parent[x] != root:
            self.parent[x], x = root, self.parent[x]
        return root

    def join(self, a, b):
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            self.parent[max(ra, rb)] = min(ra, rb)


def edge_sides(tri, corner_uv):
    """{(lo, hi): [(face, uv at lo, uv at hi), ...]} over the faces given."""
    sides = {}
    for f in range(len(tri)):
        for k in range(3):
            a, b = int(tri[f, k]), int(tri[f, (k + 1) % 3])
            ua, ub = corner_uv[f][k], corner_uv[f][(k + 1) % 3]
            key, lo_uv, hi_uv = ((a, b), ua, ub) if a < b else ((b, a), ub, ua)
            sides.setdefault(key, []).append((f, lo_uv, hi_uv))
    return sides


def charts_and_cuts(tri, uv, tri_uv, pos):
    corner_uv = [[tuple(uv[tri_uv[f, k]]) for k in range(3)] for f in range(len(tri))]
    sides = edge_sides(tri, corner_uv)
    forest = Forest(len(tri))
    cut = 0.0
    for (a, b), group in sides.items():
        is_cut = False
        for i in range(len(group)):
            for j in range(i + 1, len(group)):
                if group[i][1] == group[j][1] and group[i][2] == group[j][2]:
                    forest.join(group[i][0], group[j][0])
                else:
                    is_cut = True
        if is_cut:
            cut += float(np.linalg.norm(pos[a] - pos[b]))
    roots = [forest.find(f) for f in range(len(tri))]
    labels = {}
    chart = np.array([labels.setdefault(r, len(labels)) for r in roots], dtype=np.int64)
    return chart, len(labels), cut


def edge_inside(ax, ay, bx, by, cx, cy):
    """Coverage by one directed edge A -> B with the top-left rule, evaluated
    from the lexicographically smaller endpoint (docs/metrics.md)."""
    if (ax, ay) < (bx, by):
        w = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    else:
        w = -((ax - bx) * (cy - by) - (ay - by) * (cx - bx))
    top_left = by < ay or (by == ay and bx > ax)
    return (w > 0) | ((w == 0) & top_left)


def overlap_fraction(uv, tri_uv):
    if len(tri_uv) == 0:
        return 0.0
    used = uv[tri_uv.reshape(-1)]
    lo = used.min(axis=0)
    ext = used.max(axis=0) - lo
    side = max(ext[0], ext[1])
    if not side > 0:
        return 0.0
    s = RASTER / side
    count = np.zeros((RASTER, RASTER), dtype=np.int32)  # [row j, column i]
    for t in tri_uv:
        pts = [((uv[t[k], 0] - lo[0]) * s, (uv[t[k], 1] - lo[1]) * s) for k in range(3)]
        (x0, y0), (x1, y1), (x2, y2) = pts
        twice = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        if twice == 0:
            continue
        if twice < 0:
            pts = [pts[0], pts[2], pts[1]]
        xs = [p[0] for p in pts]
        ys = [p[1] for p in pts]
        i0 = max(0, math.floor(min(xs)) - 1)
        i1 = min(RASTER - 1, math.ceil(max(xs)))
        j0 = max(0, math.floor(min(ys)) - 1)
        j1 = min(RASTER - 1, math.ceil(max(ys)))
        if i0 > i1 or j0 > j1:
            continue
        cx = np.arange(i0, i1 + 1, dtype=np.float64)[None, :] + 0.5
        cy = np.arange(j0, j1 + 1, dtype=np.float64)[:, None] + 0.5
        inside = np.ones((j1 - j0 + 1, i1 - i0 + 1), dtype=bool)
        for k in range(3):
            (ax, ay), (bx, by) = pts[k], pts[(k + 1) % 3]
            inside &= edge_inside(ax, ay, bx, by, cx, cy)
        count[j0:j1 + 1, i0:i1 + 1] += inside
    covered = int(np.count_nonzero(count >= 1))
    return int(np.count_nonzero(count >= 2)) / covered if covered else 0.0


def metrics(pos, tri, uv, tri_uv):
    nan = float("nan")
    out = {}
    if len(tri) == 0:
        return out
    p0, p1, p2 = pos[tri[:, 0]], pos[tri[:, 1]], pos[tri[:, 2]]
    area3 = np.linalg.norm(np.cross(p1 - p0, p2 - p0), axis=1) / 2
    valid = area3 >= AREA_EPS * area3.mean()
    excluded = int(len(tri) - np.count_nonzero(valid))
    tri, tri_uv, area3 = tri[valid], tri_uv[valid], area3[valid]
    idx = np.nonzero(valid)[0]
    p0, p1, p2 = pos[tri[:, 0]], pos[tri[:, 1]], pos[tri[:, 2]]
    q0, q1, q2 = uv[tri_uv[:, 0]], uv[tri_uv[:, 1]], uv[tri_uv[:, 2]]
    d1, d2 = q1 - q0, q2 - q0
    area_uv = (d1[:, 0] * d2[:, 1] - d2[:, 0] * d1[:, 1]) / 2
    degenerate = np.abs(area_uv) <= AREA_EPS * np.abs(area_uv).mean() if len(tri) else np.zeros(0, bool)
    good = ~degenerate

    chart, nchart, cut = charts_and_cuts(tri, uv, tri_uv, pos)
    out["charts"] = nchart

    A, a = area3[good], np.abs(area_uv[good])
    keys = ["qce_mean", "qce_p95", "qce_max", "ase_mean", "ase_abs_mean", "ase_abs_mean_chart",
            "l2_stretch", "linf_stretch", "sym_dirichlet_mean"]
    if len(A) == 0:
        out.update({k: nan for k in keys})
    else:
        s1, s2 = singular_values((p1 - p0)[good], (p2 - p0)[good], d1[good], d2[good], A, area_uv[good])
        W = A.sum()
        qce = s1 / s2
        out["qce_mean"] = float((A * qce).sum() / W)
        order = np.lexsort((idx[good], qce))
        run = np.cumsum(A[order])
        out["qce_p95"] = float(qce[order][np.nonzero(run >= 0.95 * run[-1])[0][0]])
        out["qce_max"] = float(qce.max())
        ase = np.log(a / A) - math.log(a.sum() / W)
        out["ase_mean"] = float((A * ase).sum() / W)
        out["ase_abs_mean"] = float((A * np.abs(ase)).sum() / W)
        c = chart[good]
        chart_a = np.bincount(c, weights=a, minlength=nchart)
        chart_A = np.bincount(c, weights=A, minlength=nchart)
        ase_c = np.log(a / A) - np.log(chart_a[c] / chart_A[c])
        out["ase_abs_mean_chart"] = float((A * np.abs(ase_c)).sum() / W)
        sigma = math.sqrt(W / a.sum())
        gamma_big, gamma_small = 1 / (sigma * s2), 1 / (sigma * s1)
        out["l2_stretch"] = math.sqrt(float((A * (gamma_big ** 2 + gamma_small ** 2) / 2).sum() / W))
        out["linf_stretch"] = float(gamma_big.max())
        t1, t2 = sigma * s1, sigma * s2
        out["sym_dirichlet_mean"] = float((A * (t1 ** 2 + t2 ** 2 + t1 ** -2 + t2 ** -2)).sum() / W)

    sign = np.sign(area_uv)
    vote = np.bincount(chart[good], weights=(area3 * sign)[good], minlength=nchart)
    majority = np.where(vote >= 0, 1.0, -1.0)
    out["flipped"] = int(np.count_nonzero(sign[good] != majority[chart[good]]))
    out["degenerate_uv"] = int(np.count_nonzero(degenerate))
    out["overlap_fraction"] = overlap_fraction(uv, tri_uv[good])
    used = uv[tri_uv.reshape(-1)]
    inside = bool(np.all((used >= -UNIT_TOL) & (used <= 1 + UNIT_TOL)))
    out["packing_efficiency"] = float(np.abs(area_uv).sum()) if inside else nan
    out["seam_length"] = cut / math.sqrt(area3.sum())
    out["excluded_faces"] = excluded
    return out


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 1:
        sys.exit(__doc__)
    pos, tri, uv, tri_uv = read_obj(args[0], "--float32" in sys.argv)
    if len(uv) == 0:
        sys.exit("no UVs")
    tri = weld(pos, tri)
    m = metrics(pos, tri, uv, tri_uv)
    m = {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in m.items()}
    print(json.dumps({"input": args[0], "vertices": len(pos), "faces": len(tri), "metrics": m}, indent=1))


if __name__ == "__main__":
    main()
