"""neuv.unwrap, the Atlas stages, outputs, reports, packing and metrics of
existing UVs."""
import threading

import numpy as np
import pytest

import neuv
from meshes import torus

QUICK = dict(method="lscm", iters=30, use_cache=False, resolution=256, threads=1)


@pytest.fixture(scope="module")
def mesh():
    return torus()


@pytest.fixture(scope="module")
def unwrapped(mesh):
    return neuv.unwrap(*mesh, return_report=True, **QUICK)


def test_xatlas_outputs(mesh, unwrapped):
    V, F = mesh
    vmapping, indices, uvs, report = unwrapped
    assert vmapping.dtype == np.uint32 and vmapping.ndim == 1
    assert indices.dtype == np.uint32 and indices.shape == F.shape  # the torus loses no triangle to cleaning
    assert uvs.dtype == np.float64 and uvs.shape == (len(vmapping), 2)
    assert vmapping.max() < len(V) and indices.max() < len(vmapping)
    assert len(vmapping) > len(V)  # split along the seams
    assert uvs.min() >= 0 and uvs.max() <= 1
    # Each output triangle is its input triangle (cleaning keeps their order here).
    np.testing.assert_array_equal(V[vmapping[indices]], V[F])
    assert report["charts"] >= 1 and report["metrics"]["flipped"] == 0


def test_cleaning_drops_triangles():
    V, F = torus(12, 6)
    dirty = np.vstack([F, F[:1], [[0, 0, 1]]])  # a duplicate and a degenerate triangle
    vmapping, indices, uvs, report = neuv.unwrap(V, dirty, return_report=True, **QUICK)
    assert indices.shape == F.shape
    assert report["cleaning"]["duplicate_faces"] == 1 and report["cleaning"]["degenerate_faces"] == 1
    assert report["input_faces"] == len(dirty) and report["faces"] == len(F)


def test_report_has_provenance(unwrapped):
    report = unwrapped[3]
    assert {"network_area_fraction", "sources"} <= set(report["provenance"])
    assert report["method"] == "lscm" and report["input"] == ""
    assert report["threads"] == 1 and report["pack"]["resolution"] == 256


def test_stages_one_by_one_equal_generate(mesh, unwrapped):
    vmapping, indices, uvs, report = unwrapped
    with neuv.Atlas() as atlas:
        assert atlas.add_mesh(*mesh) == 0 and atlas.stage == 0 and atlas.chart_count == 0
        atlas.compute_charts(iters=30, use_cache=False, threads=1)
        assert atlas.stage == 1 and atlas.chart_count >= 1
        atlas.parameterize(method="lscm", threads=1)
        atlas.pack(resolution=256)
        assert atlas.stage == 3 and atlas.chart_count == report["charts"]
        v2, i2, uv2, face_chart = atlas.get_output(0)
        np.testing.assert_array_equal(v2, vmapping)
        np.testing.assert_array_equal(i2, indices)
        np.testing.assert_array_equal(uv2, uvs)
        assert face_chart.shape == (len(indices),) and set(face_chart) == set(range(atlas.chart_count))
        metrics = atlas.metrics
        assert metrics == pytest.approx(report["metrics"], nan_ok=True)
        # Packing again at another resolution starts from stage 2: the same charts, placed anew.
        atlas.pack(resolution=512, padding=4)
        assert atlas.report["pack"]["resolution"] == 512
        assert not np.array_equal(atlas.get_output(0)[2], uvs)


def test_several_meshes(mesh):
    small = torus(12, 6, R=0.5, r=0.2)
    with neuv.Atlas() as atlas:
        assert atlas.add_mesh(*mesh) == 0
        assert atlas.add_mesh(*small) == 1 and atlas.mesh_count == 2
        atlas.generate(**QUICK)
        for (V, F), i in ((mesh, 0), (small, 1)):
            vmapping, indices, uvs, face_chart = atlas.get_output(i)
            assert indices.shape == F.shape and vmapping.max() < len(V)
            np.testing.assert_array_equal(V[vmapping[indices]], V[F])
        with pytest.raises(neuv.Error, match="the atlas has 2 meshes"):
            atlas.get_output(2)


def test_input_types(unwrapped):
    """Lists, float32 and int16 arrays go in like float64 and uint32 ones."""
    V, F = torus(12, 6)
    a = neuv.unwrap(V, F, **QUICK)
    b = neuv.unwrap(V.tolist(), F.astype(np.int16).tolist(), **QUICK)
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)
    c = neuv.unwrap(V.astype(np.float32), F.astype(np.uint16), **QUICK)
    assert c[1].shape == F.shape


def test_two_threads_two_atlases():
    """The GIL is released during the calls: two atlases on two threads give
    what they give one after the other."""
    meshes = [torus(12, 6), torus(14, 7)]
    alone = [neuv.unwrap(*m, **QUICK)[2] for m in meshes]
    results = [None, None]

    def work(i):
        results[i] = neuv.unwrap(*meshes[i], **QUICK)[2]

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(alone, results):
        np.testing.assert_array_equal(a, b)


def test_pack_and_evaluate(mesh, unwrapped):
    V, F = mesh
    vmapping, indices, uvs, report = unwrapped
    Vo = V[vmapping]  # the output mesh: per-vertex UVs, split along seams
    metrics = neuv.evaluate(Vo, indices, uvs)
    assert metrics["charts"] == report["charts"]
    assert metrics == pytest.approx(report["metrics"], nan_ok=True)
    # The same UVs per corner, on the input mesh.
    assert neuv.evaluate(V, F, uvs[indices]) == pytest.approx(metrics, nan_ok=True)

    # Charts scattered outside the square, then packed back in.
    moved = uvs * 3 - 1
    assert np.isnan(neuv.evaluate(Vo, indices, moved)["packing_efficiency"])
    packed, pack_report = neuv.pack(Vo, indices, moved, resolution=256, return_report=True)
    assert packed.shape == uvs.shape and packed.min() >= 0 and packed.max() <= 1
    assert pack_report["charts"] == report["charts"] and pack_report["attempts"] >= 1
    after = neuv.evaluate(Vo, indices, packed)
    assert after["charts"] == report["charts"] and after["qce_mean"] == pytest.approx(metrics["qce_mean"], rel=1e-6)
    # The packing's threads change nothing in the result.
    np.testing.assert_array_equal(neuv.pack(Vo, indices, moved, resolution=256, threads=1),
                                  neuv.pack(Vo, indices, moved, resolution=256, threads=2))
    corners = neuv.pack(V, F, moved[indices], resolution=256)
    assert corners.shape == (len(F), 3, 2)
    np.testing.assert_allclose(corners, packed[indices], rtol=0, atol=1e-12)


def test_pack_charts_touching_at_a_vertex():
    """Two triangles sharing only vertex 0 are two charts: packed apart, that
    vertex needs two UVs, which per-corner UVs hold and per-vertex ones cannot."""
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [-1, 0, 0], [-1, -1, 0]], float)
    F = np.array([[0, 1, 2], [0, 3, 4]])
    uv = V[:, :2]
    with pytest.raises(ValueError, match="vertex 0 joins charts .* pass per-corner UVs"):
        neuv.pack(V, F, uv, resolution=64)
    corners = neuv.pack(V, F, uv[F], resolution=64)
    assert corners.min() >= 0 and corners.max() <= 1 and not np.array_equal(corners[0, 0], corners[1, 0])
    assert neuv.evaluate(V, F, corners)["charts"] == 2


def box(n=6):
    """An axis-aligned cube, n by n quads per side, two triangles each."""
    V, F, index = [], [], {}
    for axis in range(3):
        for side in (-1.0, 1.0):
            ids = np.empty((n + 1, n + 1), int)
            for i in range(n + 1):
                for j in range(n + 1):
                    p = [0.0, 0.0, 0.0]
                    p[axis] = side
                    p[(axis + 1) % 3] = -1 + 2 * i / n
                    p[(axis + 2) % 3] = -1 + 2 * j / n
                    ids[i, j] = index.setdefault(tuple(p), len(index))
                    if ids[i, j] == len(V):
                        V.append(p)
            for i in range(n):
                for j in range(n):
                    a, b, c, d = ids[i, j], ids[i + 1, j], ids[i + 1, j + 1], ids[i, j + 1]
                    F += [[a, b, c], [a, c, d]] if side > 0 else [[a, c, b], [a, d, c]]
    return np.array(V), np.array(F)


def test_seam_angle_keeps_the_cube_edges():
    V, F = box()
    vmapping, indices, uvs, report = neuv.unwrap(V, F, return_report=True, seam_angle=60, **QUICK)
    assert report["seams"]["required_edges"] == 12 * 6 and report["seams"]["crossed"] == 0
    # No output vertex (one UV) is shared by faces on two sides of the cube.
    normals = np.round(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), 9)
    side = np.argmax(np.abs(normals), 1) * 2 + (normals.max(1) > 0)
    owner = {}
    for t, tri in enumerate(indices):
        for v in tri:
            assert owner.setdefault(int(v), side[t]) == side[t]
    assert report["metrics"]["flipped"] == 0 and report["metrics"]["overlap_fraction"] == 0
    with pytest.raises(ValueError):
        neuv.unwrap(V, F, seam_angle=200, **QUICK)


def test_seam_edges_are_never_crossed(mesh):
    V, F = mesh
    m = 12  # torus() rings: vertex i * m + j
    ring = np.array([[5 * m + j, 5 * m + (j + 1) % m] for j in range(m)])
    vmapping, indices, uvs, report = neuv.unwrap(V, F, return_report=True, seam_edges=ring, **QUICK)
    assert report["seams"]["required_edges"] == m and report["seams"]["user_pairs"] == m
    assert report["seams"]["crossed"] == 0
    for a, b in ring:
        faces = [t for t in range(len(F)) if a in F[t] and b in F[t]]
        assert len(faces) == 2
        out = [{int(F[t][k]): int(indices[t][k]) for k in range(3)} for t in faces]
        assert out[0][a] != out[1][a] or out[0][b] != out[1][b]  # a different UV on each side
    with pytest.raises(TypeError):
        neuv.unwrap(V, F, seam_edges=[1, 2, 3], **QUICK)


def test_unwrap_file_keeps_what_the_file_carries(tmp_path):
    # A strip of 6 quads in two materials with UVs of its own, as OBJ and PLY.
    obj = ["mtllib strip.mtl"]
    obj += [f"v {i} {j} {0.1 * (i % 3)}" for i in range(7) for j in (0, 1)]
    obj += [f"vt {0.1 * i:.6g} {0.5 * j:.6g}" for i in range(7) for j in (0, 1)]
    quads = [(2 * i + 1, 2 * i + 3, 2 * i + 4, 2 * i + 2) for i in range(6)]
    for i, q in enumerate(quads):
        if i % 3 == 0:
            obj.append(f"usemtl m{i // 3}")
        obj.append("f " + " ".join(f"{v}/{v}" for v in q))
    (tmp_path / "strip.obj").write_text("\n".join(obj) + "\n")
    report = neuv.unwrap_file(tmp_path / "strip.obj", tmp_path / "out.obj", method="lscm", use_cache=False)
    assert report["polygons"] == {"input": 6, "split": 0}
    lines = (tmp_path / "out.obj").read_text().splitlines()
    faces = [ln.split()[1:] for ln in lines if ln.startswith("f ")]
    assert [len(f) for f in faces] == [4] * 6
    assert [[int(c.split("/")[0]) for c in f] for f in faces] == [list(q) for q in quads]
    assert [ln for ln in lines if ln.startswith(("usemtl", "mtllib"))] == ["mtllib strip.mtl", "usemtl m0", "usemtl m1"]
    # The file's UVs as the first set: refused for OBJ, kept in PLY.
    with pytest.raises(neuv.Error, match="OBJ holds one UV set"):
        neuv.unwrap_file(tmp_path / "strip.obj", tmp_path / "two.obj", uv_channel=1, method="lscm", use_cache=False)
    assert not (tmp_path / "two.obj").exists()
    neuv.unwrap_file(tmp_path / "strip.obj", tmp_path / "two.ply", uv_channel=1, method="lscm", use_cache=False)
    header = (tmp_path / "two.ply").read_bytes().split(b"end_header")[0].decode()
    assert "property float s\nproperty float t\n" in header and "property float s1\nproperty float t1\n" in header
    with pytest.raises(ValueError):
        neuv.unwrap_file(tmp_path / "strip.obj", tmp_path / "x.ply", uv_channel=2)
    with pytest.raises(neuv.Error, match="no such|cannot open"):
        neuv.unwrap_file(tmp_path / "missing.obj", tmp_path / "x.ply")


def squares(n):
    """n unit squares in the plane z = k, apart, two triangles each, UVs their (x, y)."""
    V = np.array([[x, y, k] for k in range(n) for x, y in ((0, 0), (1, 0), (1, 1), (0, 1))], float)
    F = np.array([[4 * k + a for a in t] for k in range(n) for t in ((0, 1, 2), (0, 2, 3))])
    return V, F, V[:, :2].copy()


def test_texels_per_unit_tiles(mesh):
    """texels_per_unit: 20 unit squares at 56 px per unit are 57 px boxes; with
    2 px padding a 256 px tile holds 4 by 4 of them, so 16 go into tile 1001
    and 4 into 1002, each at exactly 56 px per unit."""
    V, F, uv = squares(20)
    packed, rep = neuv.pack(V, F, uv, resolution=256, texels_per_unit=56, return_report=True)
    assert rep["tiles"] == 2 and rep["charts"] == 20 and rep["texel_scale"] == pytest.approx(56, rel=1e-12)
    tiles = neuv.uv_tiles(V, F, packed)
    assert [(t["udim"], t["charts"], t["faces"]) for t in tiles] == [(1001, 16, 32), (1002, 4, 8)]
    assert tiles[0]["efficiency"] == pytest.approx(16 * (56 / 256) ** 2, rel=1e-12)
    assert tiles[1]["efficiency"] == pytest.approx(4 * (56 / 256) ** 2, rel=1e-12)
    q = packed[F]
    cell = np.floor(q.mean(axis=1))
    assert (q - cell[:, None, :]).min() >= 2 / 256 - 1e-12 and (cell[:, None, :] + 1 - q).min() >= 2 / 256 - 1e-12
    side = np.linalg.norm(q[::2, 1] - q[::2, 0], axis=1)  # a side of each square
    np.testing.assert_allclose(side, 56 / 256, rtol=1e-12)
    # Refusals: a square larger than a tile, a negative density, keep_scale with it.
    with pytest.raises(neuv.Error, match="too large for one 256 px tile"):
        neuv.pack(V, F, uv, resolution=256, texels_per_unit=300)
    with pytest.raises(ValueError, match="texels_per_unit"):
        neuv.pack(V, F, uv, texels_per_unit=-1)
    with pytest.raises(neuv.Error, match="relative scales"):
        neuv.pack(V, F, uv, texels_per_unit=56, keep_scale=True)

    # unwrap: the torus at 0.9 of the density its one-square packing reached fits one tile, 1001.
    V, F = mesh
    vmapping, indices, uvs, report = neuv.unwrap(V, F, return_report=True, **QUICK)
    area = 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1).sum()
    eff = report["pack"]["efficiency"]
    T = 0.9 * 256 * np.sqrt(eff / area)
    vmapping, indices, uvs, report = neuv.unwrap(V, F, return_report=True, texels_per_unit=T, **QUICK)
    assert [t["udim"] for t in report["tiles"]] == [1001]
    assert report["tiles"][0]["efficiency"] == pytest.approx(0.81 * eff, rel=1e-6)
    assert report["pack"]["texels_per_unit"] == pytest.approx(T)
    assert neuv.uv_tiles(V[vmapping], indices, uvs) == pytest.approx(report["tiles"])
    atlas = neuv.Atlas()
    atlas.add_mesh(V, F)
    with pytest.raises(neuv.Error, match="texels_per_unit cannot be used with keep_model"):
        atlas.generate(keep_model=True, texels_per_unit=T, **QUICK)
