"""Checks of the caller's arrays before any of them reaches C, and the
neuv_mesh_decl that describes them.

The library checks the same things (neuv_mesh_create) and stays the
backstop; checking here first gives ValueError with the array's own name and
NumPy's indexing in the message."""
import ctypes

import numpy as np

from . import _capi, _errors

_INT_MAX = 2**31 - 1


def _first(mask):
    return int(np.flatnonzero(mask.ravel())[0])


def positions(V, name="V"):
    """V as a C-contiguous (N, 3) float64 array: finite real numbers."""
    a = np.asarray(V)
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"{name} must be an (N, 3) array of vertex positions, got shape {a.shape}")
    if a.dtype.kind not in "fiu":
        raise ValueError(f"{name} must hold real numbers (float), got dtype {a.dtype}")
    if a.shape[0] == 0:
        raise ValueError(f"{name} has no vertices")
    if a.shape[0] > _INT_MAX // 3:
        raise ValueError(f"{name} has {a.shape[0]} vertices, more than neuv takes ({_INT_MAX // 3})")
    a = np.ascontiguousarray(a, dtype=np.float64)
    finite = np.isfinite(a)
    if not finite.all():
        i = _first(~finite.all(axis=1))
        raise ValueError(f"{name}[{i}] = {a[i].tolist()} is not finite")
    return a


def faces(F, vertex_count, name="F", vertices="V"):
    """F as a C-contiguous (M, 3) uint32 array of indices into vertex_count vertices."""
    a = np.asarray(F)
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"{name} must be an (M, 3) array of triangles (vertex indices), got shape {a.shape}")
    if a.shape[0] == 0:
        raise ValueError(f"{name} has no triangles")
    if a.dtype.kind not in "iu":
        raise ValueError(f"{name} must hold integer vertex indices, got dtype {a.dtype}")
    if a.shape[0] > _INT_MAX // 3:
        raise ValueError(f"{name} has {a.shape[0]} triangles, more than neuv takes ({_INT_MAX // 3})")
    bad = (a < 0) | (a >= vertex_count)
    if bad.any():
        c = _first(bad)
        f, k = divmod(c, 3)
        raise ValueError(f"{name}[{f}, {k}] = {int(a[f, k])} is outside 0..{vertex_count - 1} "
                         f"({vertices} has {vertex_count} vertices)")
    return np.ascontiguousarray(a, dtype=np.uint32)


def uvs(UV, vertex_count, face_count, name="uvs"):
    """UV as float64: (N, 2) per vertex or (M, 3, 2) per corner. Returns
    (array, per_corner)."""
    a = np.asarray(UV)
    if a.shape == (vertex_count, 2):
        per_corner = False
    elif a.shape == (face_count, 3, 2):
        per_corner = True
    else:
        raise ValueError(f"{name} must be ({vertex_count}, 2) (per vertex) or ({face_count}, 3, 2) (per corner), "
                         f"got shape {a.shape}")
    if a.dtype.kind not in "fiu":
        raise ValueError(f"{name} must hold real numbers (float), got dtype {a.dtype}")
    a = np.ascontiguousarray(a, dtype=np.float64)
    finite = np.isfinite(a)
    if not finite.all():
        i = np.unravel_index(_first(~finite), a.shape)[:-1]
        raise ValueError(f"{name}[{', '.join(map(str, i))}] = {a[i].tolist()} is not finite")
    return a, per_corner


def decl(V, F=None, UV=None):
    """A neuv_mesh_decl over checked arrays (float64 positions and UVs,
    uint32 indices or None: the vertices three by three). The arrays must
    outlive the call that reads the decl."""
    d = _capi.MeshDecl()
    d.positions = V.ctypes.data
    d.position_type = _capi.FLOAT64
    d.vertex_count = V.shape[0]
    if F is not None:
        d.indices = F.ctypes.data
        d.index_type = _capi.UINT32
        d.index_count = F.size
    if UV is not None:
        d.uvs = UV.ctypes.data
        d.uv_type = _capi.FLOAT64
    return d


def create_mesh(V, F, UV=None, per_corner=False):
    """A new neuv_mesh (release with neuv_mesh_free) from checked arrays;
    UVs per vertex as given, or per corner on the vertices taken three by
    three (the library welds coinciding positions where it needs shared
    edges)."""
    if per_corner:
        # Named, so that they live until neuv_mesh_create has copied them.
        V, F, UV = np.ascontiguousarray(V[F.ravel()]), None, np.ascontiguousarray(UV.reshape(-1, 2))
    d = decl(V, F, UV)
    mesh = ctypes.c_void_p()
    _errors.check(_capi.lib.neuv_mesh_create(ctypes.byref(d), ctypes.byref(mesh)))
    return mesh
