"""The package against the neuv command on the same mesh: the same options
give the same atlas, and models cross between them both ways."""
import json
import subprocess

import numpy as np
import pytest

import neuv
from meshes import read_obj, torus, write_obj

# Quick settings (a few seconds per run on a loaded machine); one thread on
# both sides, as the output bytes are reproducible for a given thread count.
QUICK = ["--no-cache", "--iters", "30", "--resolution", "256", "--threads", "1", "--quiet"]
QUICK_PY = dict(use_cache=False, iters=30, resolution=256, threads=1)


def run(cli, *args):
    p = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    assert p.returncode == 0, f"neuv {' '.join(map(str, args))}: exit {p.returncode}: {p.stderr}"
    return p


def strip_timings(report):
    """The report without what varies from run to run (docs/report.md) or names the input."""
    r = json.loads(json.dumps(report))
    for key in ("seconds", "input"):
        r.pop(key)
    r["patches"].pop("iterations_per_second")
    r["param"].pop("refine_seconds", None)
    r["pack"].pop("split_seconds", None)
    for key in ("train_seconds", "inference_seconds"):
        r.get("model", {}).pop(key, None)
    return r


def assert_same_atlas(obj_path, V, vmapping, indices, uvs):
    """The CLI's OBJ and the Python arrays: the same triangles, per-corner UVs within 1e-9."""
    cv, ct, cf, cft = read_obj(obj_path)
    assert cf.shape == indices.shape
    np.testing.assert_array_equal(cv[cf], V[vmapping[indices]])  # positions are written exactly
    np.testing.assert_allclose(ct[cft], uvs[indices], rtol=0, atol=1e-9)


@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    d = tmp_path_factory.mktemp("cli")
    V, F = torus()
    V2, F2 = torus(flip=True)  # the same surface triangulated along the other diagonals
    write_obj(d / "torus.obj", V, F)
    write_obj(d / "torus2.obj", V2, F2)
    return d, (V, F), (V2, F2)


def test_lscm_round_trip(cli, meshes):
    d, (V, F), _ = meshes
    run(cli, "unwrap", d / "torus.obj", "-o", d / "lscm.obj", "--report", d / "lscm.json", "--method", "lscm", *QUICK)
    vmapping, indices, uvs, report = neuv.unwrap(V, F, method="lscm", return_report=True, **QUICK_PY)
    assert_same_atlas(d / "lscm.obj", V, vmapping, indices, uvs)
    cli_report = json.load(open(d / "lscm.json"))
    assert report["charts"] == cli_report["charts"] >= 1
    assert strip_timings(report) == strip_timings(cli_report)


@pytest.fixture(scope="module")
def cli_model(cli, meshes):
    """A surface model saved by `neuv unwrap --save-model`, and the atlas of that run."""
    d = meshes[0]
    run(cli, "unwrap", d / "torus.obj", "-o", d / "cli-src.obj", "--save-model", d / "cli.neuv", *QUICK)
    return d / "cli.neuv", d / "cli-src.obj"


def test_model_from_python_applied_by_cli(cli, meshes, cli_model):
    d, (V, F), (V2, F2) = meshes
    with neuv.Atlas() as atlas:
        atlas.add_mesh(V, F)
        atlas.generate(keep_model=True, **QUICK_PY)
        model = atlas.take_model()
        source = atlas.get_output(0)
    assert not model.is_category
    model.save(d / "py.neuv")
    # The CLI's --save-model run with the same options made the same atlas.
    assert_same_atlas(cli_model[1], V, *source[:3])

    run(cli, "unwrap", d / "torus2.obj", "--model", d / "py.neuv", "-o", d / "py-by-cli.obj",
        "--report", d / "py-by-cli.json", "--no-cache", "--threads", "1", "--quiet")
    with neuv.Atlas() as atlas:
        atlas.add_mesh(V2, F2)
        atlas.apply_model(model, use_cache=False, threads=1)
        vmapping, indices, uvs, _ = atlas.get_output(0)
        report = atlas.report
    assert_same_atlas(d / "py-by-cli.obj", V2, vmapping, indices, uvs)
    cli_report = json.load(open(d / "py-by-cli.json"))
    assert report["model"]["charts_from"]
    assert strip_timings(report) == strip_timings(cli_report)


def test_model_from_cli_applied_by_python(cli, meshes, cli_model):
    d, _, (V2, F2) = meshes
    run(cli, "unwrap", d / "torus2.obj", "--model", cli_model[0], "-o", d / "cli-by-cli.obj",
        "--no-cache", "--threads", "1", "--quiet")
    model = neuv.Model.load(cli_model[0])
    assert not model.is_category
    vmapping, indices, uvs = neuv.unwrap(V2, F2, model=model, use_cache=False, threads=1)
    assert_same_atlas(d / "cli-by-cli.obj", V2, vmapping, indices, uvs)
    # A path works as well as a loaded model.
    again = neuv.unwrap(V2, F2, model=str(cli_model[0]), use_cache=False, threads=1)
    np.testing.assert_array_equal(again[2], uvs)


def test_category_model_from_python_applied_by_cli(cli, tmp_path):
    shapes = [torus(16, 8, r=0.3), torus(16, 8, r=0.4)]
    # Settings that keep it to about a second: two patches, no refinement, a small atlas.
    model, report = neuv.train_category(shapes, iters=20, patch_iters=20, charts=2, refine=0, resolution=128,
                                        use_cache=False, threads=1, return_report=True)
    assert model.is_category and report["shapes"] == 2
    model.save(tmp_path / "category.neuv")
    assert neuv.Model.load(tmp_path / "category.neuv").is_category

    V, F = torus(16, 8, r=0.35)  # unseen by the training
    write_obj(tmp_path / "new.obj", V, F)
    run(cli, "unwrap", tmp_path / "new.obj", "--model", tmp_path / "category.neuv", "--shared-layer",
        "-o", tmp_path / "new-uv.obj", "--no-cache", "--threads", "1", "--quiet")
    vmapping, indices, uvs = neuv.unwrap(V, F, model=tmp_path / "category.neuv", shared_layer=True,
                                         use_cache=False, threads=1)
    assert_same_atlas(tmp_path / "new-uv.obj", V, vmapping, indices, uvs)

    # Fine-tuned with keep_model (the CLI's --finetune N --save-model): the
    # same atlas, and a surface model of this shape that reproduces it.
    with neuv.Atlas() as atlas:
        atlas.add_mesh(V, F)
        atlas.apply_model(model, finetune=3, keep_model=True, resolution=256, use_cache=False, threads=1)
        tuned = atlas.take_model()
        fine = atlas.get_output(0)[2].copy()
        assert atlas.report["pack"]["resolution"] == 256
    assert not tuned.is_category
    run(cli, "unwrap", tmp_path / "new.obj", "--model", tmp_path / "category.neuv", "--finetune", "3",
        "--resolution", "256", "--save-model", tmp_path / "tuned.neuv", "-o", tmp_path / "tuned-uv.obj",
        "--no-cache", "--threads", "1", "--quiet")
    assert not neuv.Model.load(tmp_path / "tuned.neuv").is_category
    vmapping, indices, uvs = neuv.unwrap(V, F, model=tmp_path / "tuned.neuv", use_cache=False, threads=1)
    # The networks are float32 and evaluated here chart by chart, in training over
    # every vertex at once: OpenBLAS may round the last bit of a row differently in
    # another batch, and a chart's head (weights up to ~300 on this tiny torus)
    # amplifies it. Measured 1.3e-6 at most; 1e-5 is a hundredth of a texel at
    # 1024 px, far below anything a texture shows, and far above a real change.
    np.testing.assert_allclose(uvs, fine, rtol=0, atol=1e-5)
    # What does not apply to the model's kind raises, as the CLI refuses it.
    with pytest.raises(neuv.Error, match="resolution"):
        neuv.unwrap(V, F, model=tuned, resolution=512)
    with pytest.raises(neuv.Error, match="keep_model"):
        neuv.unwrap(V, F, model=model, keep_model=True)
