"""Finding the `neuv` Python package from inside Blender.

Blender 3.4 in Debian runs the system python3.11 with Debian's NumPy, so the
package as the repository has it (python/, which loads build/libneuv.so) or
as `make python` installs it (.venv/lib/python3.11/site-packages, with its
own copy of the library) works once its folder is on sys.path. That folder
comes from the add-on's preference "neuv Python path", else from the
environment variable NEUV_PYTHONPATH (folders separated by ':'). An import
that fails is tried again on the next call, so fixing the path needs no
restart."""
import importlib
import os
import sys


class Missing(Exception):
    """The package could not be imported; str() says where it was looked for."""


def search_paths(pref_path):
    paths = []
    if pref_path:
        paths.append(pref_path)
    paths += [p for p in os.environ.get("NEUV_PYTHONPATH", "").split(os.pathsep) if p]
    return [os.path.abspath(os.path.expanduser(p)) for p in paths]


def load(pref_path=""):
    """The neuv module, its folder put first on sys.path. Raises Missing."""
    paths = search_paths(pref_path)
    for p in reversed(paths):
        if p in sys.path:
            sys.path.remove(p)
        sys.path.insert(0, p)
    importlib.invalidate_caches()
    try:
        import neuv
    except ImportError as e:
        where = ", ".join(paths) if paths else "nowhere: the add-on's preference and NEUV_PYTHONPATH are empty"
        raise Missing(f"cannot import the neuv package ({e}); looked in {where}. Set the add-on's "
                      "'neuv Python path' to the repository's python/ folder (after building it) "
                      "or to .venv/lib/python3.11/site-packages (after `make python`)") from e
    return neuv
