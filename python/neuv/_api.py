"""Atlas, Model and the one-call functions over libneuv's public API."""
import contextlib
import ctypes
import json
import os
import threading
from ctypes import byref

import numpy as np

from . import _arrays, _capi, _options
from ._callbacks import Session
from ._errors import Error, check, take_string

lib = _capi.lib


def _path(path):
    return os.fsencode(os.fspath(path))


def _struct_dict(s):
    return {name: getattr(s, name) for name, _ in s._fields_}


class Model:
    """A saved unwrap of one surface (Atlas.take_model) or a category model
    (train_category), in memory. Model.load reads one; save writes one."""

    def __init__(self, handle):
        # From take_model, train_category or load only.
        self._h = handle

    @classmethod
    def load(cls, path):
        h = ctypes.c_void_p()
        check(lib.neuv_model_load(_path(path), byref(h)), path)
        return cls(h)

    def _handle(self):
        if not self._h:
            raise ValueError("the model is closed")
        return self._h

    def save(self, path):
        """Writes the model atomically (a temporary file, then a rename)."""
        check(lib.neuv_model_save(self._handle(), _path(path)), path)

    @property
    def is_category(self):
        """True for a category model, False for a surface model."""
        return bool(lib.neuv_model_is_category(self._handle()))

    def close(self):
        """Releases the model now (else when it is garbage collected)."""
        if getattr(self, "_h", None):
            lib.neuv_model_free(self._h)
            self._h = None

    __del__ = close

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        if not self._h:
            return "<neuv.Model closed>"
        return f"<neuv.Model {'category' if self.is_category else 'surface'}>"


class Atlas:
    """One or more meshes, the stages run on them, the packed atlas
    (neuv_atlas). progress, if given, is the default progress function of
    every stage; each stage call may pass its own."""

    def __init__(self, progress=None):
        self.progress = progress
        self._busy = threading.Lock()
        self._owner = None
        h = ctypes.c_void_p()
        check(lib.neuv_atlas_create(byref(h)))
        self._h = h

    @contextlib.contextmanager
    def _locked(self):
        """One atlas runs one call at a time (the GIL is released during
        each): another thread waits; a call from inside one of the atlas's
        own callbacks would wait for itself, so it raises."""
        if self._owner == threading.get_ident():
            raise RuntimeError("neuv.Atlas: called again from inside one of its own callbacks")
        with self._busy:
            self._owner = threading.get_ident()
            try:
                yield self._handle()
            finally:
                self._owner = None

    def close(self):
        """Releases the atlas now (else when it is garbage collected)."""
        if getattr(self, "_h", None):
            with self._locked() as h:
                lib.neuv_atlas_destroy(h)
                self._h = None

    def __del__(self):
        if getattr(self, "_h", None):
            lib.neuv_atlas_destroy(self._h)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _handle(self):
        if not self._h:
            raise ValueError("the atlas is closed")
        return self._h

    def _call(self, fn, *args, progress=None):
        """fn(atlas, *args) with this call's callbacks; raises what failed."""
        with self._locked() as h:
            session = Session(progress if progress is not None else self.progress)
            lib.neuv_atlas_set_callbacks(h, byref(session.struct))
            try:
                status = fn(h, *args)
            finally:
                lib.neuv_atlas_set_callbacks(h, None)
            session.finish(status)

    def add_mesh(self, V, F):
        """Adds a mesh: V (N, 3) positions, F (M, 3) vertex indices. Several
        meshes are unwrapped as the components of one and packed into one
        square; get_output(i) gives the i-th. Returns its index. Adding
        discards any stage already run."""
        V = _arrays.positions(V)
        F = _arrays.faces(F, V.shape[0])
        d = _arrays.decl(V, F)
        self._call(lib.neuv_atlas_add_mesh, byref(d))
        return self.mesh_count - 1

    @property
    def mesh_count(self):
        return lib.neuv_atlas_mesh_count(self._handle())

    @property
    def stage(self):
        """The last stage run: 0 none, 1 charts, 2 parameterized, 3 packed."""
        return lib.neuv_atlas_stage(self._handle())

    @property
    def chart_count(self):
        """Charts after the last stage run (0 before compute_charts)."""
        return lib.neuv_atlas_chart_count(self._handle())

    def compute_charts(self, *, progress=None, **options):
        """Stage 1: cleaning, operators, PatchNet charts. Options: preset,
        charts, max_distortion, iters, seed, threads, use_cache, seam_angle
        (degrees: edges whose faces' normals differ by more are required seams),
        seam_edges ((n, 2) vertex indices, numbered across the added meshes:
        edges no chart crosses)."""
        o = _options.make(_capi.ChartOptions, options, _options.CHART, "Atlas.compute_charts")
        self._call(lib.neuv_atlas_compute_charts, byref(o), progress=progress)

    def parameterize(self, *, progress=None, **options):
        """Stage 2: each chart flattened, repaired, refined. Options: method,
        preset, iters, refine, seed, threads, allow_overlaps."""
        o = _options.make(_capi.ParamOptions, options, _options.PARAM, "Atlas.parameterize")
        self._call(lib.neuv_atlas_parameterize, byref(o), progress=progress)

    def pack(self, *, progress=None, **options):
        """Stage 3: packing into one square, metrics. Options: resolution, padding, texels_per_unit, threads."""
        o = _options.make(_capi.PackOptions, options, _options.PACK, "Atlas.pack")
        self._call(lib.neuv_atlas_pack, byref(o), progress=progress)

    def generate(self, *, progress=None, **options):
        """All three stages, as `neuv unwrap` runs them (train_faces 20000 by
        default; keep_model=True gives the same atlas as without).
        Options: those of the three stages, train_faces, keep_model."""
        o = _options.unwrap(options, "Atlas.generate", _options.GENERATE)
        self._call(lib.neuv_atlas_generate, byref(o), progress=progress)

    def apply_model(self, model, *, progress=None, **options):
        """Unwraps with a model instead of training (every stage replaced).
        model: a Model or a path. Options: threads, use_cache; surface
        models: check_inference, lscm_baseline; category models:
        allow_overlaps, finetune, shared_layer, refine, resolution, padding
        (None: the model's), keep_model (with finetune: take_model() then
        gives a surface model of this shape with the fine-tuned networks).
        An option that does not apply to the model's kind raises
        neuv.Error."""
        o = _options.apply(options, "Atlas.apply_model")
        owned = None
        if not isinstance(model, Model):
            model = owned = Model.load(model)
        try:
            self._call(lib.neuv_atlas_apply_model, model._handle(), byref(o), progress=progress)
        finally:
            if owned is not None:
                owned.close()

    def take_model(self):
        """The surface model of the last generate(keep_model=True) or
        apply_model(category, finetune=N, keep_model=True); once."""
        h = ctypes.c_void_p()
        self._call(lib.neuv_atlas_take_model, byref(h))
        return Model(h)

    def get_output(self, index=0):
        """Mesh index's part of the packed atlas, as copies:
        (vmapping (V',) uint32: the input vertex of each output vertex,
         indices (M', 3) uint32 into the output vertices,
         uvs (V', 2) float64 in [0, 1],
         face_chart (M',) int32: the chart of each output triangle).
        Output vertices are split along seams; cleaning may have dropped
        degenerate or duplicate triangles (the report counts them)."""
        out = _capi.AtlasOutput()
        self._call(lib.neuv_atlas_get_output, int(index), byref(out))
        n, m = out.vertex_count, out.index_count // 3

        def copy(ptr, count, dtype):
            if count == 0:
                return np.zeros(0, dtype)
            return np.ctypeslib.as_array(ptr, shape=(count,)).astype(dtype, copy=True)

        vmapping = copy(out.xref, n, np.uint32)
        uvs = copy(out.uvs, 2 * n, np.float64).reshape(n, 2)
        indices = copy(out.indices, 3 * m, np.uint32).reshape(m, 3)
        face_chart = copy(out.face_chart, m, np.int32)
        return vmapping, indices, uvs, face_chart

    @property
    def report(self):
        """The unwrap report (docs/report.md) as a dict; after stage 3."""
        with self._locked() as h:
            text = take_string(lib.neuv_atlas_report_json(h, None, 0.0, 0.0))
            if text is None:
                raise Error(lib.neuv_last_error().decode("utf-8", "replace"), _capi.ERR_INPUT)
        return json.loads(text)

    @property
    def metrics(self):
        """The packed atlas's metrics (docs/metrics.md) as a dict."""
        m = _capi.Metrics()
        self._call(lib.neuv_atlas_get_metrics, byref(m))
        return _struct_dict(m)


def unwrap(V, F, *, model=None, return_report=False, progress=None, **options):
    """Unwraps one mesh: xatlas.parametrize's results, so that a script can
    switch by changing one line.

    V: (N, 3) float positions; F: (M, 3) integer vertex indices.
    Returns (vmapping, indices, uvs): for each output vertex the input vertex
    it came from (uint32), the output triangles (M', 3) uint32, the UVs
    (N', 2) float64 in [0, 1]; with return_report=True the report dict too.
    Options (as `neuv unwrap`'s flags): method ('neural', 'lscm',
    'harmonic'), preset ('fast', 'paper'), charts ('auto' or K),
    max_distortion, iters, refine, seed, threads, resolution, padding,
    allow_overlaps, use_cache, train_faces, seam_angle, seam_edges. With model (a Model or a path),
    the model is applied instead of training, with Atlas.apply_model's
    options. progress(stage, fraction, detail) returns False to cancel
    (neuv.Cancelled)."""
    if model is None:
        o = _options.unwrap(options, "neuv.unwrap")
    else:
        _options.apply(options, "neuv.unwrap (with a model)")
    with Atlas(progress=progress) as atlas:
        atlas.add_mesh(V, F)
        if model is None:
            atlas._call(lib.neuv_atlas_generate, byref(o))
        else:
            atlas.apply_model(model, **options)
        vmapping, indices, uvs, _ = atlas.get_output(0)
        if return_report:
            return vmapping, indices, uvs, atlas.report
        return vmapping, indices, uvs


def unwrap_file(path, output, *, uv_channel=0, model=None, progress=None, **options):
    """Unwraps a mesh file and writes it back with the atlas, as `neuv
    unwrap PATH -o OUTPUT` does: the mesh as read (vertices, polygons,
    normals, materials, groups, colours, other properties) with the atlas
    as its UVs (docs/formats.md). uv_channel 0: the atlas replaces the
    file's UVs; 1: the file's UVs stay the first set and the atlas is the
    second (PLY, glTF; refused for OBJ and for a file without UVs). Options
    and model as for unwrap. Returns the report dict."""
    if uv_channel not in (0, 1):
        raise ValueError("uv_channel must be 0 (the atlas replaces the UVs) or 1 (a second UV set)")
    if model is None:
        o = _options.unwrap(options, "neuv.unwrap_file")
    else:
        _options.apply(options, "neuv.unwrap_file (with a model)")
    mesh = ctypes.c_void_p()
    check(lib.neuv_mesh_load(_path(path), None, byref(mesh)), path)
    try:
        with Atlas(progress=progress) as atlas:
            atlas._call(lib.neuv_atlas_add_loaded_mesh, mesh)
            if model is None:
                atlas._call(lib.neuv_atlas_generate, byref(o))
            else:
                atlas.apply_model(model, **options)
            out = ctypes.c_void_p()
            atlas._call(lib.neuv_atlas_output_mesh, 0, mesh, int(uv_channel), byref(out))
            try:
                check(lib.neuv_mesh_save(out, _path(output)), output)
            finally:
                lib.neuv_mesh_free(out)
            return atlas.report
    finally:
        lib.neuv_mesh_free(mesh)


def train_category(shapes, *, return_report=False, progress=None, **options):
    """Trains a category model on several shapes [(V, F), ...] (neural
    method). Options: preset, charts, max_distortion, iters, patch_iters,
    refine, seed, threads, resolution, padding, use_cache. Returns a Model,
    or (Model, report dict) with return_report=True."""
    _options.check_names(options, _options.TRAIN, "neuv.train_category")
    options = dict(options)
    patch_iters = _options.CONVERTERS["patch_iters"]("patch_iters", options.pop("patch_iters", 0))
    o = _options.make(_capi.UnwrapOptions, options, _options.TRAIN, "neuv.train_category")
    checked = []
    for i, shape in enumerate(shapes):
        try:
            V, F = shape
        except (TypeError, ValueError):
            raise ValueError(f"shapes[{i}] must be a pair (V, F)") from None
        V = _arrays.positions(V, f"shapes[{i}] V")
        checked.append((V, _arrays.faces(F, V.shape[0], f"shapes[{i}] F", f"shapes[{i}] V")))
    if not checked:
        raise ValueError("train_category needs at least one shape")
    meshes = (ctypes.c_void_p * len(checked))()
    try:
        for i, (V, F) in enumerate(checked):
            meshes[i] = _arrays.create_mesh(V, F).value
        session = Session(progress)
        h = ctypes.c_void_p()
        report = _capi.TrainReport()
        status = lib.neuv_train_category(meshes, len(checked), byref(o), patch_iters, byref(session.struct),
                                         byref(h), byref(report))
        model = Model(h) if h else None
        try:
            session.finish(status)
        except BaseException:
            if model is not None:
                model.close()
            raise
    finally:
        for m in meshes:
            lib.neuv_mesh_free(m)
    if return_report:
        return model, json.loads(take_string(lib.neuv_train_report_json(byref(report), None)))
    return model


def _uv_mesh(V, F, uvs):
    V = _arrays.positions(V)
    F = _arrays.faces(F, V.shape[0])
    UV, per_corner = _arrays.uvs(uvs, V.shape[0], F.shape[0])
    return V, F, UV, per_corner, _arrays.create_mesh(V, F, UV, per_corner)


def pack(V, F, uvs, *, return_report=False, **options):
    """Repacks the charts (UV-connected components) of existing UVs into one
    square, or with texels_per_unit=T at T pixels per unit of surface length
    into as many resolution-sized UDIM tiles as that takes (uv_tiles lists
    them). uvs: (N, 2) per vertex or (M, 3, 2) per corner; the result has
    the same layout. Options: resolution, padding, keep_scale,
    texels_per_unit, threads. With return_report=True also {'charts', 'attempts',
    'texel_scale', 'tiles'}."""
    o = _options.make(_capi.PackOptions, options, _options.PACK_UVS, "neuv.pack")
    V, F, UV, per_corner, mesh = _uv_mesh(V, F, uvs)
    try:
        report = _capi.PackReport()
        check(lib.neuv_pack_uvs(mesh, byref(o), None, byref(report)))
        corners = np.empty((F.shape[0], 3, 2), np.float64)
        lib.neuv_mesh_get_corner_uvs(mesh, corners.ctypes.data_as(ctypes.POINTER(ctypes.c_double)))
    finally:
        lib.neuv_mesh_free(mesh)
    if per_corner:
        result = corners
    else:
        # Corners of one vertex share its UV and so moved alike, unless the
        # vertex joins two charts that touch only there; a vertex no
        # triangle uses keeps its UV.
        result = UV.copy()
        result[F.ravel()] = corners.reshape(-1, 2)
        apart = (result[F] != corners).any(axis=2)
        if apart.any():
            v = int(F[apart][0])
            raise ValueError(f"vertex {v} joins charts that touch only at it and were packed apart, so one UV "
                             "per vertex cannot hold the result: pass per-corner UVs (uvs[F], shape (M, 3, 2))")
    return (result, _struct_dict(report)) if return_report else result


def uv_tiles(V, F, uvs):
    """The UDIM tiles UVs lie in (neuv_uv_tiles): a list of dicts {'udim',
    'charts', 'faces', 'efficiency'} by udim, tile k = 1001 + u0 + 10 v0
    being the square [u0, u0+1] x [v0, v0+1]; [] when a face leaves its tile.
    uvs: (N, 2) per vertex or (M, 3, 2) per corner."""
    V, F, UV, per_corner, mesh = _uv_mesh(V, F, uvs)
    tiles = ctypes.POINTER(_capi.UvTile)()
    count = ctypes.c_int(0)
    try:
        check(lib.neuv_uv_tiles(mesh, byref(tiles), byref(count)))
        result = [_struct_dict(tiles[i]) for i in range(count.value)]
    finally:
        lib.neuv_free(tiles)
        lib.neuv_mesh_free(mesh)
    return result


def evaluate(V, F, uvs):
    """The metrics (docs/metrics.md) of UVs on a mesh, as `neuv eval`
    computes them (coinciding positions welded first). uvs: (N, 2) per
    vertex or (M, 3, 2) per corner. Returns a dict."""
    V, F, UV, per_corner, mesh = _uv_mesh(V, F, uvs)
    try:
        m = _capi.Metrics()
        check(lib.neuv_evaluate(mesh, None, byref(m)))
    finally:
        lib.neuv_mesh_free(mesh)
    return _struct_dict(m)
