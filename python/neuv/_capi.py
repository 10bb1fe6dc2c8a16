"""The C interface of libneuv.so (include/neuv/neuv.h) as ctypes declarations.

Every struct here mirrors the header field for field; tests/test_layout.py
compiles the header and compares sizes and offsets, so a change to the header
that is not made here fails a test instead of corrupting memory.
"""
import ctypes
import os
from ctypes import (CFUNCTYPE, POINTER, Structure, c_char_p, c_double, c_int, c_size_t, c_uint,
                    c_ulonglong, c_void_p)

# neuv_status
OK, ERR_INTERNAL, ERR_INPUT, ERR_IO, ERR_NOMEM, ERR_CANCELLED = range(6)
# neuv_scalar_type, neuv_index_type
FLOAT32, FLOAT64 = 0, 1
UINT32, UINT16, INT32 = 0, 1, 2
# neuv_log_level
LOG_LEVELS = {0: "debug", 1: "info", 2: "warn"}
# neuv_method, neuv_preset
METHODS = {"neural": 0, "lscm": 1, "harmonic": 2}
PRESETS = {"fast": 0, "paper": 1}

LOG_FN = CFUNCTYPE(None, c_void_p, c_int, c_char_p)
PROGRESS_FN = CFUNCTYPE(c_int, c_void_p, c_char_p, c_double, c_char_p)


class Callbacks(Structure):
    _fields_ = [("log", LOG_FN), ("progress", PROGRESS_FN), ("user", c_void_p)]


class MeshDecl(Structure):
    _fields_ = [("positions", c_void_p), ("position_type", c_int), ("position_stride", c_size_t),
                ("vertex_count", c_int), ("indices", c_void_p), ("index_type", c_int),
                ("index_count", c_int), ("uvs", c_void_p), ("uv_type", c_int), ("uv_stride", c_size_t)]


class ChartOptions(Structure):
    _fields_ = [("preset", c_int), ("charts", c_int), ("max_distortion", c_double), ("iters", c_int),
                ("seed", c_ulonglong), ("threads", c_int), ("use_cache", c_int), ("max_memory_mb", c_int),
                ("seam_angle", c_double), ("seam_edges", c_void_p), ("seam_edge_count", c_int),
                ("hard_edges", c_int)]


class ParamOptions(Structure):
    _fields_ = [("method", c_int), ("preset", c_int), ("iters", c_int), ("refine", c_int),
                ("seed", c_ulonglong), ("threads", c_int), ("allow_overlaps", c_int)]


class PackOptions(Structure):
    _fields_ = [("resolution", c_int), ("padding", c_int), ("keep_scale", c_int), ("texels_per_unit", c_double),
                ("threads", c_int)]


class UnwrapOptions(Structure):
    _fields_ = [("method", c_int), ("preset", c_int), ("charts", c_int), ("max_distortion", c_double),
                ("iters", c_int), ("refine", c_int), ("seed", c_ulonglong), ("threads", c_int),
                ("resolution", c_int), ("padding", c_int), ("allow_overlaps", c_int), ("use_cache", c_int),
                ("keep_model", c_int), ("train_faces", c_int), ("max_memory_mb", c_int),
                ("seam_angle", c_double), ("seam_edges", c_void_p), ("seam_edge_count", c_int),
                ("hard_edges", c_int), ("texels_per_unit", c_double)]


class ApplyOptions(Structure):
    _fields_ = [("threads", c_int), ("use_cache", c_int), ("allow_overlaps", c_int),
                ("check_inference", c_int), ("lscm_baseline", c_int), ("finetune", c_int),
                ("shared_layer", c_int), ("refine", c_int), ("resolution", c_int), ("padding", c_int),
                ("keep_model", c_int)]


class Metrics(Structure):
    _fields_ = [("charts", c_int), ("qce_mean", c_double), ("qce_p95", c_double), ("qce_max", c_double),
                ("ase_mean", c_double), ("ase_abs_mean", c_double), ("ase_abs_mean_chart", c_double),
                ("l2_stretch", c_double), ("linf_stretch", c_double), ("sym_dirichlet_mean", c_double),
                ("flipped", c_int), ("degenerate_uv", c_int), ("overlap_fraction", c_double),
                ("packing_efficiency", c_double), ("seam_length", c_double), ("excluded_faces", c_int)]


class AtlasOutput(Structure):
    _fields_ = [("vertex_count", c_int), ("xref", POINTER(c_int)), ("uvs", POINTER(c_double)),
                ("index_count", c_int), ("indices", POINTER(c_uint)), ("face_chart", POINTER(c_int))]


class TrainReport(Structure):
    _fields_ = [("shapes", c_int), ("faces", c_int), ("charts", c_int), ("patch_k", c_int),
                ("patch_iterations", c_int), ("param_iterations", c_int), ("patch_loss", c_double),
                ("param_loss", c_double), ("seconds_operators", c_double), ("seconds_patches", c_double),
                ("seconds_charts", c_double), ("seconds_param", c_double), ("seconds", c_double)]


class PackReport(Structure):
    _fields_ = [("charts", c_int), ("attempts", c_int), ("texel_scale", c_double), ("tiles", c_int)]


class UvTile(Structure):
    _fields_ = [("udim", c_int), ("charts", c_int), ("faces", c_int), ("efficiency", c_double)]


# The structs the layout test checks against the header: C name -> class.
STRUCTS = {
    "neuv_callbacks": Callbacks, "neuv_mesh_decl": MeshDecl, "neuv_chart_options": ChartOptions,
    "neuv_param_options": ParamOptions, "neuv_pack_options": PackOptions,
    "neuv_unwrap_options": UnwrapOptions, "neuv_apply_options": ApplyOptions, "neuv_metrics": Metrics,
    "neuv_atlas_output": AtlasOutput, "neuv_train_report": TrainReport, "neuv_pack_report": PackReport,
    "neuv_uv_tile": UvTile,
}

_P = c_void_p  # opaque neuv_mesh *, neuv_atlas *, neuv_model *
_PP = POINTER(c_void_p)

# name: (return type, argument types). char * results that the caller frees
# are declared c_void_p so that ctypes does not convert (and lose) the pointer.
FUNCTIONS = {
    "neuv_last_error": (c_char_p, []),
    "neuv_status_name": (c_char_p, [c_int]),
    "neuv_version": (c_char_p, []),
    "neuv_free": (None, [c_void_p]),
    "neuv_mesh_create": (c_int, [POINTER(MeshDecl), _PP]),
    "neuv_mesh_free": (None, [_P]),
    "neuv_mesh_load": (c_int, [c_char_p, POINTER(Callbacks), _PP]),
    "neuv_mesh_save": (c_int, [_P, c_char_p]),
    "neuv_mesh_face_count": (c_int, [_P]),
    "neuv_mesh_get_corner_uvs": (c_int, [_P, POINTER(c_double)]),
    "neuv_unwrap_options_init": (None, [POINTER(UnwrapOptions)]),
    "neuv_chart_options_init": (None, [POINTER(ChartOptions)]),
    "neuv_param_options_init": (None, [POINTER(ParamOptions)]),
    "neuv_pack_options_init": (None, [POINTER(PackOptions)]),
    "neuv_apply_options_init": (None, [POINTER(ApplyOptions)]),
    "neuv_evaluate": (c_int, [_P, POINTER(Callbacks), POINTER(Metrics)]),
    "neuv_pack_uvs": (c_int, [_P, POINTER(PackOptions), POINTER(Callbacks), POINTER(PackReport)]),
    "neuv_atlas_create": (c_int, [_PP]),
    "neuv_atlas_destroy": (None, [_P]),
    "neuv_atlas_set_callbacks": (None, [_P, POINTER(Callbacks)]),
    "neuv_atlas_add_mesh": (c_int, [_P, POINTER(MeshDecl)]),
    "neuv_atlas_add_loaded_mesh": (c_int, [_P, _P]),
    "neuv_atlas_output_mesh": (c_int, [_P, c_int, _P, c_int, _PP]),
    "neuv_atlas_mesh_count": (c_int, [_P]),
    "neuv_atlas_compute_charts": (c_int, [_P, POINTER(ChartOptions)]),
    "neuv_atlas_parameterize": (c_int, [_P, POINTER(ParamOptions)]),
    "neuv_atlas_pack": (c_int, [_P, POINTER(PackOptions)]),
    "neuv_atlas_generate": (c_int, [_P, POINTER(UnwrapOptions)]),
    "neuv_uv_tiles": (c_int, [_P, POINTER(POINTER(UvTile)), POINTER(c_int)]),
    "neuv_atlas_stage": (c_int, [_P]),
    "neuv_atlas_chart_count": (c_int, [_P]),
    "neuv_atlas_get_output": (c_int, [_P, c_int, POINTER(AtlasOutput)]),
    "neuv_atlas_get_metrics": (c_int, [_P, POINTER(Metrics)]),
    "neuv_atlas_report_json": (c_void_p, [_P, c_char_p, c_double, c_double]),
    "neuv_model_load": (c_int, [c_char_p, _PP]),
    "neuv_model_save": (c_int, [_P, c_char_p]),
    "neuv_model_free": (None, [_P]),
    "neuv_model_is_category": (c_int, [_P]),
    "neuv_atlas_take_model": (c_int, [_P, _PP]),
    "neuv_atlas_apply_model": (c_int, [_P, _P, POINTER(ApplyOptions)]),
    "neuv_train_category": (c_int, [POINTER(c_void_p), c_int, POINTER(UnwrapOptions), c_int,
                                    POINTER(Callbacks), _PP, POINTER(TrainReport)]),
    "neuv_train_report_json": (c_void_p, [POINTER(TrainReport), c_char_p]),
}


def candidates():
    """Where the library is looked for, in order: next to this package (an
    installed copy), $NEUV_LIBRARY, the repository's build folder."""
    here = os.path.dirname(os.path.abspath(__file__))
    paths = [os.path.join(here, "libneuv.so")]
    if os.environ.get("NEUV_LIBRARY"):
        paths.append(os.environ["NEUV_LIBRARY"])
    paths.append(os.path.join(here, os.pardir, os.pardir, "build", "libneuv.so"))
    return paths


def libgomp_loaded():
    """Whether this process has libgomp already (its wait policy is then fixed)."""
    try:
        with open("/proc/self/maps") as f:
            return any("libgomp" in line for line in f)
    except OSError:
        return True


def prefer_passive_openmp():
    """libgomp reads OMP_WAIT_POLICY once, when it is loaded, and by default
    its idle threads spin: on a busy machine they take the cores the working
    threads need (bench/RESULTS.md, "OpenMP wait policy": spot on 2 threads,
    274 s against 49 s with PASSIVE). When libneuv is what brings libgomp
    in, the package sets PASSIVE first, unless the user chose a policy."""
    if "OMP_WAIT_POLICY" not in os.environ and not libgomp_loaded():
        os.environ["OMP_WAIT_POLICY"] = "PASSIVE"


def load():
    """Opens the first library found and declares its functions."""
    prefer_passive_openmp()
    tried = candidates()
    for path in tried:
        if os.path.exists(path):
            break
    else:
        raise ImportError("neuv: libneuv.so not found; looked for " + ", ".join(map(os.path.normpath, tried)) +
                          " (build it with `make python`, or set NEUV_LIBRARY to its path)")
    lib = ctypes.CDLL(os.path.realpath(path))
    for name, (restype, argtypes) in FUNCTIONS.items():
        f = getattr(lib, name)
        f.restype = restype
        f.argtypes = argtypes
    return lib, os.path.realpath(path)


lib, library_path = load()
