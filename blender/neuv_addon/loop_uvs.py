"""neuv's atlas as one UV per Blender loop. NumPy only (no bpy), so that it
can be read and tried outside Blender.

Blender keeps UVs per loop (a corner of a polygon). neuv unwraps the
polygons' triangulation (Mesh.loop_triangles) and returns its own output
vertices, split along seams, and triangles that follow the *cleaned* mesh:
positions welded, degenerate and duplicate triangles dropped, components
reoriented (docs/report.md "Cleaning"; neuv.h, neuv_atlas_get_output). So
each Blender triangle is found again by the vertices it joins, not by its
position in the list, and three things neuv's triangles allow and Blender's
polygons do not are settled here:

- a chart that cleaning turned over (wound against Blender's faces) would
  show mirrored; it is mirrored back inside its own box;
- a seam through a polygon (say along a quad's diagonal) cannot be held:
  the polygon takes the chart of its largest triangle, and each corner that
  chart lacks is placed from an edge already placed by the similarity that
  maps the triangle's 3D shape onto it (so it keeps its shape and winding);
- a polygon all of whose triangles cleaning dropped gets no UVs (left at 0).

Shapes: V is #V by 3 positions, tri_verts and tri_loops #T by 3 (the
vertex and the loop of each corner of each loop triangle), tri_poly #T.
"""
import numpy as np


def weld_representatives(V):
    """#V: for each vertex, the first vertex at exactly its position; neuv
    welds so, and its xref names that first vertex."""
    # + 0.0 turns -0.0 into 0.0: they compare equal in neuv's weld too.
    _, first, inverse = np.unique(np.asarray(V, np.float64) + 0.0, axis=0, return_index=True,
                                  return_inverse=True)
    return first[inverse.ravel()]


def triangle_areas(V, tri_verts):
    """#T: 3D area of each triangle."""
    a, b, c = (V[tri_verts[:, k]] for k in range(3))
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)


def match_triangles(V, tri_verts, xref, out_indices):
    """Each Blender triangle's output triangle and corners.

    Inputs: V, tri_verts as above; xref (#V' output vertices: the input
    vertex of each), out_indices (#M' by 3) from neuv's atlas output.
    Outputs: out_tri (#T: the output triangle joining the same welded
    vertices, -1 where cleaning dropped it), corner (#T by 3: for each
    corner, which corner of out_tri sits at its vertex; -1 when dropped).
    Duplicate triangles, which cleaning keeps once, share that one."""
    rep = weld_representatives(V)
    in_rep = rep[tri_verts]
    out_rep = rep[np.asarray(xref, np.int64)[out_indices]]
    keys = np.concatenate([np.sort(out_rep, axis=1), np.sort(in_rep, axis=1)])
    m = out_rep.shape[0]
    _, inverse = np.unique(keys, axis=0, return_inverse=True)
    inverse = inverse.ravel()
    first = np.full(inverse.max() + 1, m, np.int64)
    np.minimum.at(first, inverse[:m], np.arange(m))
    out_tri = first[inverse[m:]]
    out_tri[out_tri == m] = -1
    out_tri[(in_rep[:, 0] == in_rep[:, 1]) | (in_rep[:, 1] == in_rep[:, 2]) | (in_rep[:, 2] == in_rep[:, 0])] = -1
    corner = np.full(tri_verts.shape, -1, np.int64)
    ok = out_tri >= 0
    corner[ok] = (in_rep[ok][:, :, None] == out_rep[out_tri[ok]][:, None, :]).argmax(axis=2)
    return out_tri, corner


def signed_uv_areas(tri_uv):
    """#T: the signed area of each triangle's UVs, positive when its corners
    run counter-clockwise in UV in Blender's order (not flipped)."""
    a, b, c = tri_uv[:, 0], tri_uv[:, 1], tri_uv[:, 2]
    return 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))


def corner_uvs(uvs, out_indices, out_tri, corner):
    """#T by 3 by 2: each Blender corner's UV from its output triangle (0 where dropped)."""
    tri_uv = np.zeros(corner.shape + (2,))
    ok = out_tri >= 0
    tri_uv[ok] = uvs[out_indices[out_tri[ok][:, None], corner[ok]]]
    return tri_uv


def mirror_turned_charts(uvs, out_indices, face_chart, out_tri, tri_uv, area):
    """Mirrors (u -> umin + umax - u, inside the chart's box) each chart
    that, weighted by 3D area, shows mostly flipped in Blender's winding:
    one that cleaning reoriented against Blender's faces. uvs (#V' by 2) is
    changed in place. Returns the mirrored charts' ids."""
    charts = int(face_chart.max()) + 1 if face_chart.size else 0
    ok = out_tri >= 0
    votes = np.zeros(charts)
    np.add.at(votes, face_chart[out_tri[ok]], area[ok] * np.sign(signed_uv_areas(tri_uv[ok])))
    turned = np.flatnonzero(votes < 0)
    if turned.size == 0:
        return turned
    vert_chart = np.full(uvs.shape[0], -1, np.int64)
    vert_chart[out_indices.ravel()] = np.repeat(face_chart, 3)
    lo = np.full(charts, np.inf)
    hi = np.full(charts, -np.inf)
    used = vert_chart >= 0
    np.minimum.at(lo, vert_chart[used], uvs[used, 0])
    np.maximum.at(hi, vert_chart[used], uvs[used, 0])
    flip = used & np.isin(vert_chart, turned)
    c = vert_chart[flip]
    uvs[flip, 0] = lo[c] + hi[c] - uvs[flip, 0]
    return turned


def place_corner(P, uv_i, uv_j):
    """The UV of corner k of triangle (i, j, k) (P: 3 by 3 positions in that
    order) given the UVs of i and j: the similarity taking the edge i->j in
    the triangle's plane onto uv_i->uv_j, applied to k. Counter-clockwise
    in 3D about the triangle's normal stays counter-clockwise in UV."""
    e = P[1] - P[0]
    length = np.linalg.norm(e)
    if length == 0.0:
        return uv_i.copy()
    x_axis = e / length
    d = P[2] - P[0]
    x = float(d @ x_axis)
    y = float(np.linalg.norm(d - x * x_axis))
    z = complex(*(uv_j - uv_i)) / length * complex(x, y)
    return uv_i + np.array([z.real, z.imag])


def loop_uvs(V, tri_verts, tri_loops, tri_poly, loop_count, tri_uv, tri_chart):
    """One UV per loop.

    Inputs: V, tri_verts, tri_loops, tri_poly as above; loop_count;
    tri_uv (#T by 3 by 2: each corner's UV from its output triangle) and
    tri_chart (#T: its chart, -1 where dropped).
    Outputs: uv (loop_count by 2), have (loop_count: the loop got a UV),
    placed (the polygons some of whose corners place_corner placed),
    dropped (the polygons all of whose triangles cleaning dropped)."""
    uv = np.zeros((loop_count, 2))
    have = np.zeros(loop_count, bool)
    if tri_poly.size == 0:
        return uv, have, np.zeros(0, np.int64), np.zeros(0, np.int64)
    area = np.where(tri_chart >= 0, triangle_areas(V, tri_verts), -1.0)
    # The chart of each polygon's largest kept triangle.
    order = np.lexsort((-area, tri_poly))
    starts = np.flatnonzero(np.r_[True, tri_poly[order][1:] != tri_poly[order][:-1]])
    poly_chart = np.full(int(tri_poly.max()) + 1, -1, np.int64)
    poly_chart[tri_poly[order[starts]]] = tri_chart[order[starts]]
    keep = (tri_chart >= 0) & (tri_chart == poly_chart[tri_poly])
    uv[tri_loops[keep]] = tri_uv[keep]
    have[tri_loops[keep]] = True

    # Polygons with a triangle elsewhere or dropped, but one kept: grow from it.
    placed = np.unique(tri_poly[~keep & (poly_chart[tri_poly] >= 0)])
    if placed.size:
        rows = np.flatnonzero(np.isin(tri_poly, placed))
        rows = rows[np.argsort(tri_poly[rows], kind="stable")]
        bounds = np.flatnonzero(np.r_[True, tri_poly[rows][1:] != tri_poly[rows][:-1], True])
        for s, e in zip(bounds[:-1], bounds[1:]):
            todo = [t for t in rows[s:e] if not keep[t]]
            while todo:
                left = []
                for t in todo:
                    known = have[tri_loops[t]]
                    if known.all():
                        continue
                    if known.sum() < 2:
                        left.append(t)
                        continue
                    k = int(np.flatnonzero(~known)[0])
                    i, j = (k + 1) % 3, (k + 2) % 3
                    li, lj, lk = tri_loops[t, i], tri_loops[t, j], tri_loops[t, k]
                    uv[lk] = place_corner(V[tri_verts[t, [i, j, k]]], uv[li], uv[lj])
                    have[lk] = True
                if len(left) == len(todo):
                    break  # the rest touch no placed edge
                todo = left
    dropped = np.setdiff1d(np.unique(tri_poly), np.flatnonzero(poly_chart >= 0))
    return uv, have, placed, dropped


def from_atlas(V, tri_verts, tri_loops, tri_poly, loop_count, output):
    """The whole way from neuv's output to Blender's loops.

    output: (xref, indices, uvs, face_chart) of one mesh, as
    neuv.Atlas.get_output gives them. Returns a dict: uv (loop_count by 2),
    have (loop_count), and the counts to report: dropped_triangles
    (Blender triangles cleaning dropped), dropped_polygons (left without
    UVs), placed_polygons, mirrored_charts. When the last two are not zero
    the charts no longer sit where neuv packed them: pack again."""
    xref, out_indices, uvs, face_chart = output
    out_indices = np.asarray(out_indices, np.int64)
    uvs = np.array(uvs, np.float64)
    out_tri, corner = match_triangles(V, tri_verts, xref, out_indices)
    area = triangle_areas(V, tri_verts)
    tri_uv = corner_uvs(uvs, out_indices, out_tri, corner)
    mirrored = mirror_turned_charts(uvs, out_indices, face_chart, out_tri, tri_uv, area)
    if mirrored.size:
        tri_uv = corner_uvs(uvs, out_indices, out_tri, corner)
    tri_chart = np.where(out_tri >= 0, np.asarray(face_chart, np.int64)[out_tri], -1)
    uv, have, placed, dropped = loop_uvs(V, tri_verts, tri_loops, tri_poly, loop_count, tri_uv, tri_chart)
    return {"uv": uv, "have": have, "dropped_triangles": int((out_tri < 0).sum()),
            "dropped_polygons": int(dropped.size), "placed_polygons": int(placed.size),
            "mirrored_charts": int(mirrored.size)}
