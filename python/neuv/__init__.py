"""neuv: neural UV unwrapping of triangle meshes, on NumPy arrays.

    import neuv
    vmapping, indices, uvs = neuv.unwrap(V, F, method="lscm")

unwrap gives xatlas.parametrize's three arrays; unwrap_file unwraps a
file and writes it back with what it carries (as `neuv unwrap`); Atlas runs the stages one by
one (and several meshes in one atlas); Model, train_category, pack and
evaluate cover saved models, category models and existing UV maps. Options
are the CLI's flags in snake_case. Failures of the library raise
neuv.Error (neuv.Cancelled when the progress function cancels); bad arrays
raise ValueError before anything reaches C.

The library is libneuv.so, looked for next to this package, then at
$NEUV_LIBRARY, then in the repository's build folder (neuv.library_path).
"""
from ._capi import lib as _lib, library_path
from ._errors import Cancelled, Error
from ._api import Atlas, Model, evaluate, pack, train_category, unwrap, unwrap_file, uv_tiles

__version__ = _lib.neuv_version().decode()
__all__ = ["Atlas", "Cancelled", "Error", "Model", "evaluate", "library_path", "pack", "train_category", "unwrap",
           "unwrap_file", "uv_tiles"]
