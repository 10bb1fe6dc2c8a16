"""Keyword options, named as the CLI's flags in snake_case, into the
library's option structs.

Each struct starts from the library's own defaults (neuv_*_options_init);
only the options given are set. An option no call of this kind takes is a
TypeError naming it; a value of the wrong type is a TypeError, a value out
of the CLI's range a ValueError (the library checks ranges too)."""
import ctypes
import difflib
import numbers

from . import _capi


def _integer(name, value, low=None, high=None):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"option {name} must be an integer, got {value!r}")
    value = int(value)
    if (low is not None and value < low) or (high is not None and value > high):
        span = f"at least {low}" if high is None else f"in {low}..{high}"
        raise ValueError(f"option {name} must be {span}, got {value}")
    return value


def _flag(name, value):
    if not isinstance(value, (bool, numbers.Integral)) or value not in (0, 1):
        raise TypeError(f"option {name} must be True or False, got {value!r}")
    return int(bool(value))


def _choice(table):
    def convert(name, value):
        if value not in table:
            raise ValueError(f"option {name} must be one of {', '.join(map(repr, table))}, got {value!r}")
        return table[value]
    return convert


def _charts(name, value):
    if value is None or value == "auto":
        return 0
    if isinstance(value, str):
        raise ValueError(f"option charts must be 'auto' or a count in 1..4096, got {value!r}")
    return _integer(name, value, 0, 4096)


def _max_distortion(name, value):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"option {name} must be a number, got {value!r}")
    if not value >= 1.0 or value == float("inf"):
        raise ValueError(f"option {name} must be a finite number of at least 1, got {value!r}")
    return float(value)


def _refine(name, value):
    return _integer(name, value, 0, 1000000)


def _apply_refine(name, value):
    return -1 if value is None else _integer(name, value, -1, 1000000)


# Applying a model, None (the default) keeps the model's packing.
def _apply_resolution(name, value):
    return 0 if value is None else _integer(name, value)


def _apply_padding(name, value):
    return -1 if value is None else _integer(name, value)


def _seam_angle(name, value):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"option {name} must be a number, got {value!r}")
    if not 0 <= value < 180:
        raise ValueError(f"option {name} must be an angle in degrees in [0, 180) (0: no seams), got {value!r}")
    return float(value)


def _texels_per_unit(name, value):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"option {name} must be a number, got {value!r}")
    if not 0 <= value < float("inf"):
        raise ValueError(f"option {name} must be a finite number of pixels per unit of surface length "
                         f"(0: off), got {value!r}")
    return float(value)


def _set_seam_edges(struct, name, value):
    """seam_edges: pairs of vertex indices, anything NumPy reads as (n, 2)
    integers. The array lives on the struct (as _seam_edges) for as long as
    the struct, so the pointer stays valid during the call."""
    import numpy as np
    edges = np.asarray(value)
    if edges.size == 0:
        edges = edges.reshape(0, 2)
    if edges.ndim != 2 or edges.shape[1] != 2 or not np.issubdtype(edges.dtype, np.integer):
        raise TypeError(f"option {name} must be pairs of vertex indices, shape (n, 2) integers, "
                        f"got shape {edges.shape} of {edges.dtype}")
    if len(edges) and (edges.min() < 0 or edges.max() > 2**31 - 1):
        raise ValueError(f"option {name} holds an index out of range ({edges.min()}..{edges.max()})")
    struct._seam_edges = np.ascontiguousarray(edges, dtype=np.int32)
    struct.seam_edges = struct._seam_edges.ctypes.data if len(edges) else None
    struct.seam_edge_count = len(edges)


def _train_faces(name, value):
    value = _integer(name, value, 0)
    if 0 < value < 500:
        raise ValueError(f"option {name} must be 0 (never simplify) or at least 500, got {value}")
    return value


# name -> converter(name, value) -> the C field's value; the field has the option's name.
CONVERTERS = {
    "method": _choice(_capi.METHODS),
    "preset": _choice(_capi.PRESETS),
    "charts": _charts,
    "max_distortion": _max_distortion,
    "iters": lambda n, v: _integer(n, v, 0),
    "refine": _refine,
    "seed": lambda n, v: _integer(n, v, 0, 2**64 - 1),
    "threads": lambda n, v: _integer(n, v, 0),
    "resolution": lambda n, v: _integer(n, v),
    "padding": lambda n, v: _integer(n, v),
    "allow_overlaps": _flag,
    "use_cache": _flag,
    "keep_model": _flag,
    "train_faces": _train_faces,
    "seam_angle": _seam_angle,
    "seam_edges": None,  # two fields: _set_seam_edges
    "hard_edges": _flag,
    "keep_scale": _flag,
    "texels_per_unit": _texels_per_unit,
    "check_inference": _flag,
    "lscm_baseline": _flag,
    "shared_layer": _flag,
    "finetune": lambda n, v: _integer(n, v, 0, 1000000),
    "patch_iters": lambda n, v: _integer(n, v, 0, 10000000),
    "max_memory_mb": lambda n, v: _integer(n, v, 0),
}

CHART = ("preset", "charts", "max_distortion", "iters", "seed", "threads", "use_cache", "max_memory_mb", "seam_angle",
         "seam_edges", "hard_edges")
PARAM = ("method", "preset", "iters", "refine", "seed", "threads", "allow_overlaps")
PACK = ("resolution", "padding", "texels_per_unit", "threads")
PACK_UVS = PACK + ("keep_scale",)
UNWRAP = tuple(dict.fromkeys(CHART + PARAM + PACK + ("train_faces",)))
GENERATE = UNWRAP + ("keep_model",)
APPLY = ("threads", "use_cache", "allow_overlaps", "check_inference", "lscm_baseline", "finetune",
         "shared_layer", "refine", "resolution", "padding", "keep_model")
TRAIN = ("preset", "charts", "max_distortion", "iters", "patch_iters", "refine", "seed", "threads",
         "resolution", "padding", "use_cache", "max_memory_mb")

# The CLI's default where it differs from the library's (src/cli/cmd_unwrap.c):
# above this many faces, train on a simplified copy and apply the model.
DEFAULT_TRAIN_FACES = 20000


def check_names(options, allowed, where):
    """TypeError for the first option not in allowed."""
    for name in options:
        if name in allowed:
            continue
        if name in CONVERTERS:
            raise TypeError(f"{where}: option '{name}' does not apply here (it takes: {', '.join(allowed)})")
        close = difflib.get_close_matches(name, CONVERTERS, n=1)
        hint = f"; did you mean '{close[0]}'?" if close else ""
        raise TypeError(f"{where}: unknown option '{name}'{hint}")


def fill(struct, options, allowed, where, converters=None):
    """Sets struct's fields from options (a dict) after checking them."""
    check_names(options, allowed, where)
    for name, value in options.items():
        if name == "seam_edges":
            _set_seam_edges(struct, name, value)
            continue
        convert = (converters or {}).get(name, CONVERTERS[name])
        setattr(struct, name, convert(name, value))
    return struct


def make(kind, options, allowed, where, converters=None):
    """kind's struct (e.g. _capi.ChartOptions) at the library's defaults,
    then the options set."""
    struct = kind()
    init = {
        _capi.ChartOptions: _capi.lib.neuv_chart_options_init,
        _capi.ParamOptions: _capi.lib.neuv_param_options_init,
        _capi.PackOptions: _capi.lib.neuv_pack_options_init,
        _capi.UnwrapOptions: _capi.lib.neuv_unwrap_options_init,
        _capi.ApplyOptions: _capi.lib.neuv_apply_options_init,
    }[kind]
    init(ctypes.byref(struct))
    return fill(struct, options, allowed, where, converters)


def unwrap(options, where, allowed=UNWRAP):
    """neuv_unwrap_options as `neuv unwrap` sets them: train_faces defaults to
    the CLI's 20000 (keep_model changes nothing else: a kept model records
    the refinement and carries it over when applied)."""
    o = make(_capi.UnwrapOptions, options, allowed, where)
    if "train_faces" not in options:
        o.train_faces = DEFAULT_TRAIN_FACES
    return o


def apply(options, where):
    return make(_capi.ApplyOptions, options, APPLY, where,
                {"refine": _apply_refine, "resolution": _apply_resolution, "padding": _apply_padding})
