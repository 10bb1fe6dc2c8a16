"""The add-on's three operators: Neural Unwrap, Pack and Apply neuv model.

Each reads the selected mesh objects (those in edit mode, in edit mode),
hands their loop triangles in world space to neuv, and writes one UV map;
the geometry is only read. Failures become Blender reports carrying the
library's message."""
import contextlib
import logging
import time

import bpy
import numpy as np
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from . import loop_uvs, package

# The library's stages in the order a run passes them (the progress
# callback's `stage`); the bar gives each the same share.
STAGES = ("simplify", "operators", "geodesic pairs", "patches", "charts", "param", "repair", "refine", "pack")


def load_neuv(context):
    addon = context.preferences.addons.get(__package__)
    return package.load(addon.preferences.python_path if addon else "")


class Progress:
    """neuv's progress callback into the window manager's progress (the
    cursor), the status bar and the console; neuv's log warnings kept for
    the operator's report."""

    def __init__(self, context, title):
        self.wm = context.window_manager
        self.workspace = context.workspace
        self.title = title
        self.value = 0.0
        self.seen = set()
        self.warnings = []
        self.handler = logging.Handler(logging.WARNING)
        self.handler.emit = lambda record: self.warnings.append(record.getMessage())

    def __enter__(self):
        self.wm.progress_begin(0, 1000)
        logging.getLogger("neuv").addHandler(self.handler)
        return self

    def __call__(self, stage, fraction, detail):
        if stage in STAGES:
            self.value = max(self.value, (STAGES.index(stage) + min(max(fraction, 0.0), 1.0)) / len(STAGES))
        self.wm.progress_update(int(1000 * self.value))
        if stage not in self.seen:  # the console: each stage once
            self.seen.add(stage)
            print(f"{self.title}: {stage}")
        if self.workspace is not None:
            self.workspace.status_text_set(f"{self.title}: {stage}" + (f", {detail}" if detail else ""))
        return True

    def __exit__(self, *exc):
        logging.getLogger("neuv").removeHandler(self.handler)
        if self.workspace is not None:
            self.workspace.status_text_set(None)
        self.wm.progress_end()


class MeshArrays:
    """One object's mesh as neuv takes it: V (#V by 3, world space, float64),
    tri_verts, tri_loops (#T by 3) and tri_poly (#T) from loop_triangles."""

    def __init__(self, obj):
        self.obj = obj
        me = obj.data
        me.calc_loop_triangles()
        t = len(me.loop_triangles)
        self.tri_verts = np.empty(3 * t, np.int32)
        self.tri_loops = np.empty(3 * t, np.int32)
        self.tri_poly = np.empty(t, np.int32)
        me.loop_triangles.foreach_get("vertices", self.tri_verts)
        me.loop_triangles.foreach_get("loops", self.tri_loops)
        me.loop_triangles.foreach_get("polygon_index", self.tri_poly)
        self.tri_verts = self.tri_verts.reshape(t, 3).astype(np.int64)
        self.tri_loops = self.tri_loops.reshape(t, 3).astype(np.int64)
        self.tri_poly = self.tri_poly.astype(np.int64)
        co = np.empty(3 * len(me.vertices), np.float32)
        me.vertices.foreach_get("co", co)
        M = np.array(obj.matrix_world, np.float64)
        self.V = co.reshape(-1, 3).astype(np.float64) @ M[:3, :3].T + M[:3, 3]
        self.loop_count = len(me.loops)
        ev = np.empty(2 * len(me.edges), np.int32)
        me.edges.foreach_get("vertices", ev)
        marked = np.zeros(len(me.edges), bool)
        me.edges.foreach_get("use_seam", marked)
        self.seams = ev.reshape(-1, 2)[marked].astype(np.int64)  # edges marked as seams
        me.edges.foreach_get("use_edge_sharp", marked)
        self.sharp = ev.reshape(-1, 2)[marked].astype(np.int64)  # edges marked sharp (hard edges)
        if t == 0:
            raise ValueError(f"{obj.name}: the mesh has no faces")

    def read_uvs(self, layer):
        uv = np.empty(2 * self.loop_count, np.float32)
        layer.data.foreach_get("uv", uv)
        return uv.reshape(-1, 2).astype(np.float64)

    def write_uvs(self, layer, uv):
        layer.data.foreach_set("uv", np.asarray(uv, np.float32).ravel())
        self.obj.data.update()


def mesh_objects(context):
    """The meshes to work on, each once: the objects in edit mode, else the
    selected mesh objects."""
    if context.mode == 'EDIT_MESH':
        objects = context.objects_in_mode_unique_data
    else:
        objects = [o for o in context.selected_objects if o.type == 'MESH']
    seen, unique = set(), []
    for o in objects:
        if o.type == 'MESH' and o.data.name_full not in seen:
            seen.add(o.data.name_full)
            unique.append(o)
    return unique


@contextlib.contextmanager
def object_mode(context):
    """Mesh data (loops, UV maps) is only current outside edit mode."""
    edit = context.mode == 'EDIT_MESH'
    if edit:
        bpy.ops.object.mode_set(mode='OBJECT')
    try:
        yield
    finally:
        if edit:
            bpy.ops.object.mode_set(mode='EDIT')


def pack_together(neuv, meshes, uvs, options):
    """Repacks the UVs of several meshes into one square, or into UDIM tiles
    with texels_per_unit (neuv.pack on all
    their triangles at once, per corner). uvs: one (loop_count by 2) array
    per mesh, changed in place; triangles with a loop that has no UV
    (NaN) stay out."""
    V, F, C, chosen, offset = [], [], [], [], 0
    for m, uv in zip(meshes, uvs):
        ok = ~np.isnan(uv[m.tri_loops]).any(axis=(1, 2))
        V.append(m.V)
        F.append(m.tri_verts[ok] + offset)
        C.append(uv[m.tri_loops[ok]])
        chosen.append(ok)
        offset += len(m.V)
    packed = neuv.pack(np.concatenate(V), np.concatenate(F), np.concatenate(C), **options)
    start = 0
    for m, uv, ok in zip(meshes, uvs, chosen):
        n = int(ok.sum())
        uv[m.tri_loops[ok]] = packed[start:start + n]
        start += n


def blender_flipped(m, uv):
    """Faces whose UVs run clockwise in Blender's winding."""
    return int((loop_uvs.signed_uv_areas(uv[m.tri_loops]) < 0).sum())


def record_metrics(neuv, m, layer):
    """neuv.evaluate on the UVs as Blender holds them (float32), kept on the
    mesh as the custom property neuv_metrics; returns the dict."""
    uv = m.read_uvs(layer)
    metrics = neuv.evaluate(m.V, m.tri_verts, uv[m.tri_loops])
    metrics["uv_map"] = layer.name
    metrics["blender_flipped"] = blender_flipped(m, uv)
    m.obj.data["neuv_metrics"] = metrics
    return metrics


def count(n, word):
    return f"{n} {word}" + ("" if n == 1 else "s")


def summary(metrics, seconds):
    charts = sum(x["charts"] for x in metrics)
    flipped = sum(x["blender_flipped"] for x in metrics)
    qce = ", ".join(f"{x['qce_mean']:.4f}" for x in metrics)
    return f"neuv: {count(charts, 'chart')}, qce_mean {qce}, {flipped} flipped, {seconds:.1f} s"


class AtlasWriter:
    """What Neural Unwrap and Apply share: the atlas's outputs onto loops,
    a second packing where polygons or charts had to change, the UV maps
    written, the reports."""

    def write(self, neuv, atlas, meshes, layers, pack_options, run):
        results = [loop_uvs.from_atlas(m.V, m.tri_verts, m.tri_loops, m.tri_poly, m.loop_count,
                                       atlas.get_output(i)) for i, m in enumerate(meshes)]
        uvs = []
        for r in results:
            uv = r["uv"].copy()
            uv[~r["have"]] = np.nan
            uvs.append(uv)
        moved = sum(r["placed_polygons"] for r in results)
        mirrored = sum(r["mirrored_charts"] for r in results)
        if moved or mirrored:
            pack_together(neuv, meshes, uvs, pack_options)
        for m, layer, uv in zip(meshes, layers, uvs):
            m.write_uvs(layer, np.nan_to_num(uv, nan=0.0))
        dropped = sum(r["dropped_polygons"] for r in results)
        if dropped:
            self.report({'WARNING'}, f"neuv: {count(dropped, 'face')} dropped by neuv's cleaning (degenerate "
                                     "or welded to nothing), UVs left at 0")
        if moved:
            self.report({'INFO'}, f"neuv: {count(moved, 'face')} crossed a seam: each moved onto one chart, "
                                  "then the atlas packed again")
        if mirrored:
            self.report({'INFO'}, f"neuv: {count(mirrored, 'chart')} wound against Blender's faces mirrored "
                                  "back, then the atlas packed again")
        for w in run.warnings[:5]:
            self.report({'WARNING'}, f"neuv: {w}")
        return [record_metrics(neuv, m, layer) for m, layer in zip(meshes, layers)]

    def target_layers(self, meshes):
        layers = []
        for m in meshes:
            me = m.obj.data
            layer = me.uv_layers.active if self.into_active else None
            if layer is None:
                layer = me.uv_layers.get(self.uv_map) or me.uv_layers.new(name=self.uv_map, do_init=False)
            if layer is None:
                raise ValueError(f"{m.obj.name}: cannot add a UV map (a mesh holds at most 8)")
            me.uv_layers.active = layer
            layers.append(layer)
        return layers

    def run(self, context, title, work):
        """work(neuv, meshes, run) -> atlas. Reports, and returns the
        operator's result."""
        try:
            neuv = load_neuv(context)
        except package.Missing as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        objects = mesh_objects(context)
        if not objects:
            self.report({'ERROR'}, "neuv: select a mesh object")
            return {'CANCELLED'}
        start = time.perf_counter()
        with object_mode(context):
            try:
                meshes = [MeshArrays(o) for o in objects]
                with Progress(context, title) as run:
                    atlas = work(neuv, meshes, run)
                    with atlas:
                        layers = self.target_layers(meshes)
                        metrics = self.write(neuv, atlas, meshes, layers, self.pack_options(), run)
            except (neuv.Error, ValueError) as e:
                self.report({'ERROR'}, f"neuv: {e}")
                return {'CANCELLED'}
        self.report({'INFO'}, summary(metrics, time.perf_counter() - start))
        return {'FINISHED'}


class NEUV_OT_unwrap(AtlasWriter, bpy.types.Operator):
    """Unwrap the selected meshes with neuv (neural charts and maps) into one atlas"""
    bl_idname = "uv.neuv_unwrap"
    bl_label = "Neural Unwrap (neuv)"
    bl_options = {'REGISTER', 'UNDO'}

    method: EnumProperty(name="Method", default='neural', items=(
        ('neural', "Neural", "The parameterization networks"),
        ('lscm', "LSCM", "Least squares conformal maps on neuv's charts (fast)"),
        ('harmonic', "Harmonic", "Cotangent harmonic maps on neuv's charts")))
    preset: EnumProperty(name="Preset", default='fast', items=(
        ('fast', "Fast", "Networks sized for a CPU"),
        ('paper', "Paper", "The published method's configuration (slow)")))
    charts: IntProperty(name="Charts", default=0, min=0, max=4096,
                        description="Patches before disk cutting; 0: automatic")
    max_distortion: FloatProperty(name="Max Distortion", default=1.15, min=1.0, max=100.0,
                                  description="Automatic charts: split until each chart's LSCM qce_mean is below it")
    iters: IntProperty(name="Iterations", default=0, min=0, description="Training steps; 0: the preset's")
    refine: IntProperty(name="Refine", default=400, min=0, max=1000000,
                        description="Neural: vertex refinement steps after the networks; 0: none")
    seed: IntProperty(name="Seed", default=1, min=0, description="Every random choice derives from it")
    resolution: IntProperty(name="Resolution", default=1024, min=64, max=16384,
                            description="Atlas side in pixels, for padding")
    padding: IntProperty(name="Padding", default=2, min=0, max=2048,
                         description="Pixels between charts and to the border")
    use_cache: BoolProperty(name="Operator Cache", default=True,
                            description="Keep the geometry operators in neuv's on-disk cache")
    texels_per_unit: FloatProperty(name="Texels per Unit", default=0.0, min=0.0, max=1e9,
                                   description="Texture pixels per unit of surface length: the charts go into "
                                               "UDIM tiles of Resolution pixels (1001, 1002, ...) as that density "
                                               "needs; 0: one square")
    use_seams: BoolProperty(name="Keep Marked Seams", default=True,
                            description="Edges marked as seams are chart borders: no chart crosses them")
    hard_edges: BoolProperty(name="Hard Edges", default=True,
                             description="Edges marked sharp are chart borders too")
    seam_angle: FloatProperty(name="Seam Angle", default=0.0, min=0.0, max=179.0,
                              description="Edges whose faces' normals differ by more than this many degrees "
                                          "are chart borders too; 0: none")
    uv_map: StringProperty(name="UV Map", default="neuv", description="The UV map written (added if missing)")
    into_active: BoolProperty(name="Into Active UV Map", default=False,
                              description="Write the active UV map instead of the one named above")

    @classmethod
    def poll(cls, context):
        return bool(mesh_objects(context))

    def pack_options(self):
        return {"resolution": self.resolution, "padding": self.padding, "texels_per_unit": self.texels_per_unit}

    def seam_options(self, meshes):
        """seam_edges (marked seams and sharp edges, numbered across the
        meshes as the atlas numbers them) and seam_angle. Seams need the networks trained on the meshes
        themselves, so with seams train_faces is 0 (docs/api.md)."""
        seams, offset = [], 0
        for m in meshes:
            if self.use_seams:
                seams.append(m.seams + offset)
            if self.hard_edges:
                seams.append(m.sharp + offset)
            offset += len(m.V)
        edges = np.concatenate(seams) if seams else np.empty((0, 2), np.int64)
        if len(edges) == 0 and self.seam_angle == 0:
            return {}
        return {"seam_edges": edges, "seam_angle": self.seam_angle, "train_faces": 0}

    def execute(self, context):
        options = dict(method=self.method, preset=self.preset, charts=self.charts,
                       max_distortion=self.max_distortion, iters=self.iters, refine=self.refine,
                       seed=self.seed, resolution=self.resolution, padding=self.padding,
                       use_cache=self.use_cache, texels_per_unit=self.texels_per_unit)

        def work(neuv, meshes, run):
            atlas = neuv.Atlas(progress=run)
            try:
                for m in meshes:
                    atlas.add_mesh(m.V, m.tri_verts)
                atlas.generate(**options, **self.seam_options(meshes))
            except BaseException:
                atlas.close()
                raise
            return atlas
        return self.run(context, "neuv unwrap", work)


class NEUV_OT_apply_model(AtlasWriter, bpy.types.Operator):
    """Unwrap the selected meshes with a saved neuv model (.neuv): a surface model's atlas carried over, or a category model's inference"""
    bl_idname = "uv.neuv_apply_model"
    bl_label = "Apply neuv Model"
    bl_options = {'REGISTER', 'UNDO'}

    filepath: StringProperty(subtype='FILE_PATH')
    filter_glob: StringProperty(default="*.neuv", options={'HIDDEN'})
    finetune: IntProperty(name="Fine-tune", default=0, min=0, max=1000000,
                          description="Category models: training steps from the model's weights (0: inference only)")
    refine: IntProperty(name="Refine", default=-1, min=-1, max=1000000,
                        description="Category models: vertex refinement steps; -1: the model's")
    use_cache: BoolProperty(name="Operator Cache", default=True,
                            description="Keep the geometry operators in neuv's on-disk cache")
    uv_map: StringProperty(name="UV Map", default="neuv", description="The UV map written (added if missing)")
    into_active: BoolProperty(name="Into Active UV Map", default=False,
                              description="Write the active UV map instead of the one named above")

    @classmethod
    def poll(cls, context):
        return bool(mesh_objects(context))

    def pack_options(self):
        return {}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}

    def execute(self, context):
        path = bpy.path.abspath(self.filepath)

        def work(neuv, meshes, run):
            with neuv.Model.load(path) as model:
                options = {"use_cache": self.use_cache}
                if model.is_category:
                    options.update(finetune=self.finetune, refine=None if self.refine < 0 else self.refine)
                atlas = neuv.Atlas(progress=run)
                try:
                    for m in meshes:
                        atlas.add_mesh(m.V, m.tri_verts)
                    atlas.apply_model(model, **options)
                except BaseException:
                    atlas.close()
                    raise
            return atlas
        return self.run(context, "neuv apply", work)


class NEUV_OT_pack(bpy.types.Operator):
    """Pack the charts of the active UV map of the selected meshes into one square with neuv"""
    bl_idname = "uv.neuv_pack"
    bl_label = "Pack (neuv)"
    bl_options = {'REGISTER', 'UNDO'}

    resolution: IntProperty(name="Resolution", default=1024, min=64, max=16384,
                            description="Atlas side in pixels, for padding")
    padding: IntProperty(name="Padding", default=2, min=0, max=2048,
                         description="Pixels between charts and to the border")
    keep_scale: BoolProperty(name="Keep Scale", default=False,
                             description="Keep the charts' relative scales instead of matching their 3D areas")
    texels_per_unit: FloatProperty(name="Texels per Unit", default=0.0, min=0.0, max=1e9,
                                   description="Texture pixels per unit of surface length: the charts go into "
                                               "UDIM tiles of Resolution pixels (1001, 1002, ...) as that density "
                                               "needs; 0: one square")

    @classmethod
    def poll(cls, context):
        return any(o.data.uv_layers.active for o in mesh_objects(context))

    def execute(self, context):
        try:
            neuv = load_neuv(context)
        except package.Missing as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        objects = [o for o in mesh_objects(context) if o.data.uv_layers.active]
        start = time.perf_counter()
        with object_mode(context):
            try:
                meshes = [MeshArrays(o) for o in objects]
                layers = [o.data.uv_layers.active for o in objects]
                uvs = [m.read_uvs(layer) for m, layer in zip(meshes, layers)]
                pack_together(neuv, meshes, uvs, {"resolution": self.resolution, "padding": self.padding,
                                                  "keep_scale": self.keep_scale,
                                                  "texels_per_unit": self.texels_per_unit})
                for m, layer, uv in zip(meshes, layers, uvs):
                    m.write_uvs(layer, uv)
                metrics = [record_metrics(neuv, m, layer) for m, layer in zip(meshes, layers)]
            except (neuv.Error, ValueError) as e:
                self.report({'ERROR'}, f"neuv: {e}")
                return {'CANCELLED'}
        self.report({'INFO'}, summary(metrics, time.perf_counter() - start))
        return {'FINISHED'}


classes = (NEUV_OT_unwrap, NEUV_OT_pack, NEUV_OT_apply_model)
