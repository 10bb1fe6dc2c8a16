"""The add-on inside Blender, run by tests/cli_blender.sh:

    blender -b --factory-startup --python-exit-code 1 --python check_addon.py -- REPO NEUV TMP

REPO the source tree, NEUV the built CLI, TMP a scratch folder; the add-on
is found through BLENDER_USER_SCRIPTS (TMP/scripts/addons/neuv_addon, a
link to blender/neuv_addon). Checks loop_uvs on hand-made atlas outputs,
then the operators on a UV sphere (quads, pole triangles) and a cylinder
with 16-gon caps, unwrapped together in edit mode: every face gets UVs,
none flipped in Blender's winding, the geometry untouched, and the metrics
the add-on records equal `neuv eval --json` on the sphere exported to OBJ.
Then Pack, Apply neuv model (a surface model saved through the package)
and an error from the library as a Blender error."""
import sys

sys.dont_write_bytecode = True  # the add-on is the source tree's, through a link

import json  # noqa: E402
import math  # noqa: E402
import os  # noqa: E402
import subprocess  # noqa: E402
import time  # noqa: E402

import addon_utils  # noqa: E402
import bpy  # noqa: E402
import numpy as np  # noqa: E402

REPO, NEUV, TMP = sys.argv[sys.argv.index("--") + 1:][:3]
failures = []
started = time.perf_counter()


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


# ---- the add-on and its preference --------------------------------------
if addon_utils.enable("neuv_addon", default_set=True, handle_error=None) is None:
    sys.exit("FAIL: the add-on neuv_addon did not enable")
prefs = bpy.context.preferences.addons["neuv_addon"].preferences
prefs.python_path = os.path.join(REPO, "python")
from neuv_addon import loop_uvs  # noqa: E402

# ---- loop_uvs on hand-made outputs ---------------------------------------
# A unit quad, corners 0..3, loops 0..3, triangles (0,1,2), (0,2,3).
Q = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
QT = np.array([[0, 1, 2], [0, 2, 3]])
QP = np.array([0, 0])

# A seam along the diagonal: the quad takes chart 0 and its corner 3 is
# placed from the diagonal, where the square continues.
out = (np.array([0, 1, 2, 0, 2, 3]), np.array([[0, 1, 2], [3, 4, 5]]),
       np.array([[.1, .1], [.3, .1], [.3, .3], [.9, .5], [.9, .9], [.5, .9]]), np.array([0, 1]))
r = loop_uvs.from_atlas(Q, QT, QT, QP, 4, out)
check(np.allclose(r["uv"], [[.1, .1], [.3, .1], [.3, .3], [.1, .3]]) and r["placed_polygons"] == 1,
      "loop_uvs: a seam through a quad's diagonal: the quad on one chart, its fourth corner placed")

# Cleaning turned the chart over: its triangles wound the other way and
# counter-clockwise in UV that way, so clockwise in Blender's winding. It
# is mirrored back inside its box.
out = (np.array([0, 1, 2, 3]), np.array([[0, 2, 1], [0, 3, 2]]),
       np.array([[.3, .1], [.1, .1], [.1, .3], [.3, .3]]), np.array([0, 0]))
r = loop_uvs.from_atlas(Q, QT, QT, QP, 4, out)
check(r["mirrored_charts"] == 1 and np.allclose(r["uv"], [[.1, .1], [.3, .1], [.3, .3], [.1, .3]]),
      "loop_uvs: a chart wound against Blender's faces is mirrored in its box")

# Cleaning dropped one triangle of the quad and the whole second face (a
# sliver); a duplicate vertex (4, at 0's position) is named by xref as 0.
V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 0], [2, 0, 0], [3, 0, 0]], float)
T = np.array([[4, 1, 2], [4, 2, 3], [1, 5, 6]])
L = np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6]])
out = (np.array([0, 1, 2]), np.array([[0, 1, 2]]), np.array([[.1, .1], [.3, .1], [.3, .3]]), np.array([0]))
r = loop_uvs.from_atlas(V, T, L, np.array([0, 0, 1]), 7, out)
check(np.allclose(r["uv"][:4], [[.1, .1], [.3, .1], [.3, .3], [.1, .3]]) and r["have"][:4].all()
      and not r["have"][4:].any() and r["dropped_polygons"] == 1 and r["dropped_triangles"] == 2,
      "loop_uvs: welded vertices matched, a dropped triangle's corner placed, a dropped face left without UVs")

# ---- the scene: a UV sphere and a cylinder with n-gon caps ----------------
bpy.ops.object.select_all(action='SELECT')
bpy.ops.object.delete()
bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12, radius=1.0, location=(0, 0, 0))
sphere = bpy.context.active_object
bpy.ops.mesh.primitive_cylinder_add(vertices=16, radius=0.5, depth=1.5, end_fill_type='NGON', location=(3, 0, 0))
cylinder = bpy.context.active_object
objects = (sphere, cylinder)
check(max(len(p.vertices) for p in cylinder.data.polygons) == 16, "the cylinder has 16-gon caps")


def geometry(obj):
    me = obj.data
    co = np.empty(3 * len(me.vertices), np.float32)
    me.vertices.foreach_get("co", co)
    loops = np.empty(len(me.loops), np.int32)
    me.loops.foreach_get("vertex_index", loops)
    return co, loops, len(me.polygons), tuple(obj.matrix_world.col[3])


def loop_triangle_uvs(obj, layer):
    me = obj.data
    me.calc_loop_triangles()
    tl = np.empty(3 * len(me.loop_triangles), np.int32)
    me.loop_triangles.foreach_get("loops", tl)
    uv = np.empty(2 * len(me.loops), np.float32)
    layer.data.foreach_get("uv", uv)
    return uv.reshape(-1, 2)[tl.reshape(-1, 3)].astype(np.float64)


def check_uvs(obj, what):
    me = obj.data
    layer = me.uv_layers.get("neuv")
    if layer is None:
        check(False, f"{obj.name}: {what}: a UV map 'neuv'")
        return None
    check(me.uv_layers.active == layer, f"{obj.name}: {what}: the UV map 'neuv' is active")
    corners = loop_triangle_uvs(obj, layer)
    areas = loop_uvs.signed_uv_areas(corners)
    per_face = np.zeros(len(me.polygons))
    polys = np.empty(len(me.loop_triangles), np.int32)
    me.loop_triangles.foreach_get("polygon_index", polys)
    np.add.at(per_face, polys, np.abs(areas))
    check((per_face > 0).all(), f"{obj.name}: {what}: every face has UVs ({len(per_face)} faces)")
    check((areas > 0).all(), f"{obj.name}: {what}: no flipped triangle ({(areas <= 0).sum()} of {len(areas)})")
    check(corners.min() >= 0 and corners.max() <= 1, f"{obj.name}: {what}: UVs in [0, 1]")
    return corners


def check_geometry(what):
    for obj, before in zip(objects, geometries):
        after = geometry(obj)
        same = (np.array_equal(before[0], after[0]) and np.array_equal(before[1], after[1])
                and before[2:] == after[2:])
        check(same, f"{obj.name}: {what}: vertices, positions, loops and faces unchanged")


geometries = [geometry(o) for o in objects]

# ---- Neural Unwrap, in edit mode, both objects into one atlas ------------
for o in objects:
    o.select_set(True)
bpy.context.view_layer.objects.active = sphere
bpy.ops.object.mode_set(mode='EDIT')
t = time.perf_counter()
result = bpy.ops.uv.neuv_unwrap(method='lscm', iters=30, use_cache=False)
print(f"unwrap: {result} in {time.perf_counter() - t:.1f} s")
check(result == {'FINISHED'}, "Neural Unwrap finished")
check(bpy.context.mode == 'EDIT_MESH', "back in edit mode")
bpy.ops.object.mode_set(mode='OBJECT')
check_geometry("unwrap")
for o in objects:
    check_uvs(o, "unwrap")
metrics = dict(sphere.data["neuv_metrics"])
check(metrics["flipped"] == 0 and metrics["blender_flipped"] == 0, "the recorded metrics: nothing flipped")

# The sphere to OBJ with its UVs; `neuv eval` on it must give the metrics
# the add-on recorded (quads come out of Blender's loop triangles and
# neuv's OBJ reader as the same fan).
bpy.ops.object.select_all(action='DESELECT')
sphere.select_set(True)
obj_path = os.path.join(TMP, "sphere.obj")
bpy.ops.export_scene.obj(filepath=obj_path, use_selection=True, use_uvs=True, use_materials=False,
                         use_normals=False, use_triangles=False, keep_vertex_order=True)
ev = subprocess.run([NEUV, "eval", obj_path, "--json"], capture_output=True, text=True)
check(ev.returncode == 0, f"neuv eval {obj_path}: {ev.stderr.strip()}")
if ev.returncode == 0:
    cli = json.loads(ev.stdout)["metrics"]
    print(f"qce_mean: add-on {metrics['qce_mean']:.9f}, neuv eval {cli['qce_mean']:.9f}")
    check(abs(cli["qce_mean"] - metrics["qce_mean"]) <= 1e-6, "neuv eval's qce_mean equals the add-on's (1e-6)")
    check(cli["flipped"] == 0 == metrics["flipped"], "neuv eval: no flipped face, as the add-on says")
    check(cli["charts"] == metrics["charts"], "neuv eval: the add-on's chart count")

# ---- Marked seams: the sphere's equator is a chart border ----------------
def polygon_uvs_at(me, uv, vertex_pairs):
    """For each edge (a, b): whether its two faces hold different UVs at a or b."""
    corner = {}
    for p in me.polygons:
        for li in p.loop_indices:
            corner[(p.index, me.loops[li].vertex_index)] = tuple(uv[li])
    faces = {}
    for p in me.polygons:
        vs = set(p.vertices)
        for a, b in vertex_pairs:
            if a in vs and b in vs:
                faces.setdefault((a, b), []).append(p.index)
    return [len(faces.get((a, b), [])) == 2 and
            (corner[(faces[(a, b)][0], a)] != corner[(faces[(a, b)][1], a)] or
             corner[(faces[(a, b)][0], b)] != corner[(faces[(a, b)][1], b)]) for a, b in vertex_pairs]


me = sphere.data
equator = []
for e in me.edges:
    a, b = e.vertices
    e.use_seam = abs(me.vertices[a].co.z) < 1e-6 and abs(me.vertices[b].co.z) < 1e-6
    if e.use_seam:
        equator.append((a, b))
check(len(equator) == 24, f"the sphere's equator marked as a seam ({len(equator)} edges)")
bpy.ops.object.select_all(action='DESELECT')
sphere.select_set(True)
bpy.context.view_layer.objects.active = sphere
result = bpy.ops.uv.neuv_unwrap(method='lscm', iters=30, use_cache=False, charts=1)
check(result == {'FINISHED'}, "Neural Unwrap with a marked seam finished")
uv = np.empty(2 * len(me.loops), np.float32)
me.uv_layers["neuv"].data.foreach_get("uv", uv)
split = polygon_uvs_at(me, uv.reshape(-1, 2), equator)
check(all(split), f"every marked seam edge is a chart border ({sum(split)} of {len(split)})")
check_uvs(sphere, "marked seams")
result = bpy.ops.uv.neuv_unwrap(method='lscm', iters=30, use_cache=False, charts=1, use_seams=False)
me.uv_layers["neuv"].data.foreach_get("uv", uv)
split = polygon_uvs_at(me, uv.reshape(-1, 2), equator)
check(result == {'FINISHED'} and not all(split),
      f"without Keep Marked Seams, one chart crosses the equator ({len(split) - sum(split)} edges)")
for e in me.edges:
    e.use_seam = False

# ---- Pack (neuv), object mode, both objects' active UV maps ---------------
for o in objects:
    o.select_set(True)
before = loop_triangle_uvs(sphere, sphere.data.uv_layers["neuv"])
result = bpy.ops.uv.neuv_pack(padding=8, resolution=512)
check(result == {'FINISHED'}, "Pack finished")
check_geometry("pack")
for o in objects:
    check_uvs(o, "pack")
check(not np.allclose(before, loop_triangle_uvs(sphere, sphere.data.uv_layers["neuv"])),
      "Pack moved the charts (another padding)")

# ---- Pack (neuv) at a texel density: UDIM tiles ------------------------------
def positions_and_triangles(obj):
    """(#V, 3) float32 positions and (#T, 3) vertex indices of Blender's triangulation."""
    me = obj.data
    me.calc_loop_triangles()
    tv = np.empty(3 * len(me.loop_triangles), np.int32)
    me.loop_triangles.foreach_get("vertices", tv)
    co = np.empty(3 * len(me.vertices), np.float32)
    me.vertices.foreach_get("co", co)
    return co.reshape(-1, 3), tv.reshape(-1, 3)


def triangle_areas_3d(obj):
    co, tv = positions_and_triangles(obj)
    p = co.astype(np.float64)[tv]
    return 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)


def density(objs):
    """Pixels of a 512 px tile per unit of surface length, over all charts."""
    uv_area = sum(np.abs(loop_uvs.signed_uv_areas(loop_triangle_uvs(o, o.data.uv_layers["neuv"]))).sum() for o in objs)
    return 512 * math.sqrt(uv_area / sum(triangle_areas_3d(o).sum() for o in objs))


T = 1.6 * density(objects)  # 2.56 times the one-square area: more than one tile
result = bpy.ops.uv.neuv_pack(padding=4, resolution=512, texels_per_unit=T)
check(result == {'FINISHED'}, "Pack at a texel density finished")
tiles = set()
for o in objects:
    c = loop_triangle_uvs(o, o.data.uv_layers["neuv"])
    lo, hi = np.floor(c.min(axis=1) * (1 - 1e-9)), np.floor(c.max(axis=1) * (1 - 1e-9))
    check((lo == hi).all(), f"{o.name}: every triangle inside one UDIM tile")
    check((loop_uvs.signed_uv_areas(c) > 0).all(), f"{o.name}: no flipped triangle in tiles")
    tiles |= {(int(u), int(v)) for u, v in lo}
check(len(tiles) >= 2, f"the charts fill {len(tiles)} tiles at {T:.1f} px per unit (expected 2 or more)")
check(abs(density(objects) / T - 1) < 1e-4, f"the density is {density(objects):.3f} px per unit, asked {T:.3f}")

result = bpy.ops.uv.neuv_unwrap(method='lscm', iters=30, use_cache=False, resolution=512, texels_per_unit=T)
check(result == {'FINISHED'}, "Neural Unwrap at a texel density finished")
tiles = set()
for o in objects:
    c = loop_triangle_uvs(o, o.data.uv_layers["neuv"])
    lo = np.floor(c.min(axis=1) * (1 - 1e-9))
    check((lo == np.floor(c.max(axis=1) * (1 - 1e-9))).all(), f"{o.name}: unwrap: every triangle inside one tile")
    tiles |= {(int(u), int(v)) for u, v in lo}
check(len(tiles) >= 2, f"unwrap: the charts fill {len(tiles)} tiles at {T:.1f} px per unit")
check(abs(density(objects) / T - 1) < 1e-4, f"unwrap: the density is {density(objects):.3f} px per unit, asked {T:.3f}")

# ---- Apply neuv model ------------------------------------------------------
# A surface model of the sphere, saved through the package, applied by the operator.
import neuv  # noqa: E402  (on sys.path now, from the preference)

co, tv = positions_and_triangles(sphere)
model_path = os.path.join(TMP, "sphere.neuv")
with neuv.Atlas() as atlas:
    atlas.add_mesh(co, tv)
    atlas.generate(method="lscm", iters=30, use_cache=False, keep_model=True)
    atlas.take_model().save(model_path)
bpy.ops.object.select_all(action='DESELECT')
sphere.select_set(True)
bpy.context.view_layer.objects.active = sphere
result = bpy.ops.uv.neuv_apply_model(filepath=model_path, use_cache=False)
check(result == {'FINISHED'}, "Apply neuv model finished")
check_geometry("apply")
check_uvs(sphere, "apply")

# A failure of the library reaches Blender as an error report with its message.
missing = os.path.join(TMP, "missing.neuv")
try:
    bpy.ops.uv.neuv_apply_model(filepath=missing)
    check(False, "applying a missing model fails")
except RuntimeError as e:
    check(missing in str(e) and "Error" in str(e), f"a missing model: a Blender error with neuv's message ({e})")

print(f"check_addon: {len(failures)} failed, {time.perf_counter() - started:.1f} s")
sys.exit(1 if failures else 0)
