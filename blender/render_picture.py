"""The picture of the README's Blender section: Suzanne unwrapped by the
add-on, rendered (Workbench) with a checker through the new UV map, beside
the UV layout as Blender exports it. Headless:

    blender -b --factory-startup --python blender/render_picture.py -- docs/img/blender-suzanne.png [METHOD]

METHOD is neural (default), lscm or harmonic. The neuv package comes from
$NEUV_PYTHONPATH, else the repository's python/ folder (build first)."""
import colorsys
import os
import sys
import tempfile

import bpy
import numpy as np
from bpy_extras.mesh_utils import mesh_linked_uv_islands
from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if not args:
    sys.exit("usage: blender -b --factory-startup --python render_picture.py -- OUT.png [METHOD]")
out_path = os.path.abspath(args[0])
method = args[1] if len(args) > 1 else "neural"
SIDE = 480

sys.dont_write_bytecode = True
sys.path.insert(0, HERE)
os.environ.setdefault("NEUV_PYTHONPATH", os.path.join(HERE, os.pardir, "python"))
import neuv_addon  # noqa: E402

neuv_addon.register()

bpy.ops.object.select_all(action='SELECT')
bpy.ops.object.delete()
bpy.ops.mesh.primitive_monkey_add(location=(0, 0, 0), rotation=(0, 0, 0.5))
monkey = bpy.context.active_object
bpy.ops.object.shade_smooth()
if bpy.ops.uv.neuv_unwrap(method=method, seed=1) != {'FINISHED'}:
    sys.exit("the unwrap failed")
metrics = dict(monkey.data["neuv_metrics"])
print(f"{method}: {metrics['charts']} charts, qce_mean {metrics['qce_mean']:.4f}, "
      f"{metrics['blender_flipped']} flipped")

# A checker through the UV map, shown by Workbench's texture colour.
checker = bpy.data.images.new("checker", 1024, 1024)
checker.generated_type = 'COLOR_GRID'
material = bpy.data.materials.new("checker")
material.use_nodes = True
node = material.node_tree.nodes.new("ShaderNodeTexImage")
node.image = checker
material.node_tree.nodes.active = node
monkey.data.materials.append(material)

scene = bpy.context.scene
scene.render.engine = 'BLENDER_WORKBENCH'
scene.display.shading.light = 'STUDIO'
scene.display.shading.color_type = 'TEXTURE'
scene.render.resolution_x = scene.render.resolution_y = SIDE
scene.render.resolution_percentage = 100
scene.render.film_transparent = False
scene.world.color = (0.55, 0.55, 0.55)
scene.render.image_settings.file_format = 'PNG'
scene.view_settings.view_transform = 'Standard'
bpy.ops.object.camera_add(location=(2.2, -5.4, 1.4))
camera = bpy.context.active_object
camera.rotation_euler = (Vector((0, 0, 0.0)) - camera.location).to_track_quat('-Z', 'Y').to_euler()
camera.data.lens = 72
scene.camera = camera

def draw_layout(me, side):
    """The active UV map as a picture (side by side by 3, rows from the top):
    each island in its colour, polygon edges dark. Drawn here because
    uv.export_layout's PNG needs a display."""
    picture = np.ones((side, side, 3))
    uv = np.empty(2 * len(me.loops), np.float32)
    me.uv_layers.active.data.foreach_get("uv", uv)
    xy = uv.reshape(-1, 2).astype(np.float64) * (side - 1)
    xy[:, 1] = side - 1 - xy[:, 1]
    island = np.zeros(len(me.polygons), np.int64)
    for i, polys in enumerate(mesh_linked_uv_islands(me)):
        island[polys] = i
    hues = (np.arange(island.max() + 1) * 0.618034) % 1.0
    colors = np.array([colorsys.hsv_to_rgb(h, 0.35, 1.0) for h in hues])
    me.calc_loop_triangles()
    for t in me.loop_triangles:
        p = xy[list(t.loops)]
        lo = np.floor(p.min(axis=0)).astype(int)
        hi = np.ceil(p.max(axis=0)).astype(int) + 1
        X, Y = np.meshgrid(np.arange(lo[0], hi[0]) + 0.5, np.arange(lo[1], hi[1]) + 0.5)
        d = (p[1, 0] - p[0, 0]) * (p[2, 1] - p[0, 1]) - (p[1, 1] - p[0, 1]) * (p[2, 0] - p[0, 0])
        if d == 0:
            continue
        w1 = ((X - p[0, 0]) * (p[2, 1] - p[0, 1]) - (Y - p[0, 1]) * (p[2, 0] - p[0, 0])) / d
        w2 = ((p[1, 0] - p[0, 0]) * (Y - p[0, 1]) - (p[1, 1] - p[0, 1]) * (X - p[0, 0])) / d
        inside = (w1 >= 0) & (w2 >= 0) & (w1 + w2 <= 1)
        picture[lo[1]:hi[1], lo[0]:hi[0]][inside[:picture.shape[0] - lo[1], :picture.shape[1] - lo[0]]] = \
            colors[island[t.polygon_index]]
    for poly in me.polygons:
        loops = list(poly.loop_indices)
        for a, b in zip(loops, loops[1:] + loops[:1]):
            n = int(np.ceil(np.abs(xy[b] - xy[a]).max())) + 2
            s = np.linspace(0, 1, n)[:, None]
            px = np.clip(np.round(xy[a] + s * (xy[b] - xy[a])).astype(int), 0, side - 1)
            picture[px[:, 1], px[:, 0]] = 0.25
    picture[[0, -1], :] = picture[:, [0, -1]] = 0.5
    return picture


with tempfile.TemporaryDirectory() as tmp:
    scene.render.filepath = os.path.join(tmp, "render.png")
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(scene.render.filepath)
    render = np.empty(SIDE * SIDE * 4, np.float32)
    image.pixels.foreach_get(render)
render = render.reshape(SIDE, SIDE, 4)[::-1, :, :3]  # Blender's rows run from the bottom
both = np.concatenate([render, draw_layout(monkey.data, SIDE)], axis=1)[::-1]
rgba = np.concatenate([both, np.ones(both.shape[:2] + (1,))], axis=2).astype(np.float32)
picture = bpy.data.images.new("picture", both.shape[1], both.shape[0])
picture.pixels.foreach_set(rgba.ravel())
settings = scene.render.image_settings  # PNG, RGB, the most compression; 'Standard' keeps colours as they are
settings.color_mode = 'RGB'
settings.compression = 100
picture.save_render(out_path, scene=scene)
print(f"wrote {out_path} ({os.path.getsize(out_path)} bytes)")
