"""Bad arrays, bad options and refused calls: an exception with a message,
never a crash."""
import numpy as np
import pytest

import neuv
from meshes import torus

V, F = torus(12, 6)
QUICK = dict(method="lscm", iters=30, use_cache=False, resolution=256, threads=1)


def nan_at(a, i, j):
    a = a.copy()
    a[i, j] = np.nan
    return a


BAD_ARRAYS = [
    (V[:, :2], F, r"V must be an \(N, 3\) array .* got shape \(72, 2\)"),
    (V.ravel(), F, r"V must be an \(N, 3\) array"),
    (V.astype(str), F, "V must hold real numbers"),
    (V.astype(complex), F, "V must hold real numbers"),
    (nan_at(V, 5, 1), F, r"V\[5\] = \[.*nan.*\] is not finite"),
    (V + np.inf, F, r"V\[0\] .* is not finite"),
    (V, F[:, :2], r"F must be an \(M, 3\) array .* got shape \(144, 2\)"),
    (V, np.hstack([F, F[:, :1]]), r"F must be an \(M, 3\) array"),
    (V, F[:0], "F has no triangles"),
    (V, np.zeros((0, 3)), "F has no triangles"),
    (V, [], r"F must be an \(M, 3\) array .* got shape \(0,\)"),
    (V, F.astype(float), "F must hold integer vertex indices, got dtype float64"),
    (V, F.astype(bool), "F must hold integer vertex indices, got dtype bool"),
    (V, np.where(F == 7, 72, F), r"F\[\d+, \d\] = 72 is outside 0..71 \(V has 72 vertices\)"),
    (V, np.where(F == 7, -1, F), r"F\[\d+, \d\] = -1 is outside 0..71"),
    (V[:0], F, "V has no vertices"),
]


@pytest.mark.parametrize("V, F, message", BAD_ARRAYS)
def test_bad_arrays(V, F, message):
    with pytest.raises(ValueError, match=message):
        neuv.unwrap(V, F, **QUICK)
    with neuv.Atlas() as atlas:
        with pytest.raises(ValueError, match=message):
            atlas.add_mesh(V, F)
        assert atlas.mesh_count == 0
    uv = np.zeros((len(np.asarray(V)) if np.ndim(V) == 2 else 0, 2))
    with pytest.raises(ValueError, match=message):
        neuv.evaluate(V, F, uv)
    with pytest.raises(ValueError):
        neuv.train_category([(V, F)])


def test_bad_uvs():
    with pytest.raises(ValueError, match=r"uvs must be \(72, 2\) \(per vertex\) or \(144, 3, 2\) \(per corner\)"):
        neuv.evaluate(V, F, np.zeros((72, 3)))
    uv = np.zeros((144, 3, 2))
    uv[9, 2, 1] = np.inf
    with pytest.raises(ValueError, match=r"uvs\[9, 2\] = \[0.0, inf\] is not finite"):
        neuv.pack(V, F, uv)


def test_library_backstop():
    """What only the library can judge comes back as neuv.Error with its message."""
    with pytest.raises(neuv.Error, match="no faces") as e:
        neuv.unwrap(V, np.array([[0, 0, 1], [2, 2, 2]]), **QUICK)  # every triangle degenerate
    assert e.value.status == 2 and e.value.status_name == "bad input"
    assert isinstance(e.value, RuntimeError)
    with pytest.raises(neuv.Error, match="resolution must be in 64..16384"):
        neuv.unwrap(V, F, **dict(QUICK, resolution=10))
    with pytest.raises(neuv.Error, match="resolution must be between 8 and 32768 px, got 4"):
        neuv.pack(V, F, np.zeros((72, 2)), resolution=4)


@pytest.mark.parametrize("options, error, message", [
    (dict(resolutoin=256), TypeError, "unknown option 'resolutoin'; did you mean 'resolution'"),
    (dict(frobnicate=1), TypeError, "neuv.unwrap: unknown option 'frobnicate'"),
    (dict(keep_scale=True), TypeError, "option 'keep_scale' does not apply here"),
    (dict(method="xatlas"), ValueError, "option method must be one of 'neural', 'lscm', 'harmonic'"),
    (dict(iters="30"), TypeError, "option iters must be an integer, got '30'"),
    (dict(iters=30.0), TypeError, "option iters must be an integer"),
    (dict(iters=-1), ValueError, "option iters must be at least 0"),
    (dict(charts="many"), ValueError, "option charts must be 'auto' or a count"),
    (dict(max_distortion=0.5), ValueError, "option max_distortion must be a finite number of at least 1"),
    (dict(seed=-1), ValueError, "option seed must be in 0..18446744073709551615"),
    (dict(use_cache="no"), TypeError, "option use_cache must be True or False"),
    (dict(train_faces=100), ValueError, "option train_faces must be 0 .* or at least 500"),
    (dict(progress=42), TypeError, "progress must be a function"),
])
def test_bad_options(options, error, message):
    with pytest.raises(error, match=message):
        neuv.unwrap(V, F, **options)


def test_options_of_another_stage():
    with neuv.Atlas() as atlas:
        atlas.add_mesh(V, F)
        with pytest.raises(TypeError, match="Atlas.compute_charts: option 'resolution' does not apply here"):
            atlas.compute_charts(resolution=256)
        with pytest.raises(TypeError, match="Atlas.pack: option 'method' does not apply here"):
            atlas.pack(method="lscm")
        with pytest.raises(TypeError, match="does not apply here"):
            neuv.unwrap(V, F, model="m.neuv", method="lscm")  # a model brings its own method
        assert atlas.stage == 0


def test_calls_out_of_order(tmp_path):
    with neuv.Atlas() as atlas:
        with pytest.raises(neuv.Error, match="no mesh added"):
            atlas.compute_charts()
        atlas.add_mesh(V, F)
        with pytest.raises(neuv.Error, match=r"compute the charts first"):
            atlas.parameterize()
        with pytest.raises(neuv.Error, match="not packed yet"):
            atlas.get_output(0)
        with pytest.raises(neuv.Error, match="stage 3|packed|report"):
            atlas.report
        atlas.generate(**QUICK)
        with pytest.raises(neuv.Error, match="keep_model"):
            atlas.take_model()
    with pytest.raises(ValueError, match="closed"):
        atlas.get_output(0)


def test_bad_model_files(tmp_path):
    with pytest.raises(neuv.Error, match="none.neuv") as e:
        neuv.Model.load(tmp_path / "none.neuv")
    assert e.value.status == 3
    (tmp_path / "junk.neuv").write_bytes(b"not a model at all" * 10)
    with pytest.raises(neuv.Error) as e:
        neuv.Model.load(tmp_path / "junk.neuv")
    assert e.value.status == 2 and str(e.value)
    with pytest.raises(neuv.Error):
        neuv.unwrap(V, F, model=tmp_path / "junk.neuv")
