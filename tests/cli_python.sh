#!/usr/bin/env bash
# The Python package (python/): its pytest suite on the built library and
# CLI (round trips, bad arrays, models both ways, cancellation, the header's
# layout), then the install of `make python` into a temporary venv, used
# from there. Skips (77) without Debian's python3-numpy or python3-pytest.
# usage: cli_python.sh /path/to/build/neuv   (the build folder is its folder)
set -u
NEUV=${1:?usage: cli_python.sh /path/to/build/neuv}
HERE=$(cd "$(dirname "$0")" && pwd)
SRC=$(cd "$HERE/.." && pwd)
BUILD=$(cd "$(dirname "$NEUV")" && pwd)
NEUV=$BUILD/$(basename "$NEUV")
# Debian's Python (NEUV_PYTHON to choose another), else the first python3 on PATH.
PY=${NEUV_PYTHON:-/usr/bin/python3}
[ -x "$PY" ] || PY=$(command -v python3) || { echo "SKIP: no python3"; exit 77; }
"$PY" -c 'import numpy' 2>/dev/null || { echo "SKIP: no NumPy for $PY (Debian: python3-numpy; make setup)"; exit 77; }
"$PY" -m pytest --version >/dev/null 2>&1 || { echo "SKIP: no pytest for $PY (Debian: python3-pytest; make setup)"; exit 77; }
[ -e "$BUILD/libneuv.so" ] || { echo "FAIL: no $BUILD/libneuv.so"; exit 1; }
# A sanitizer build's library needs the ASan runtime loaded before Python.
if readelf -d "$BUILD/libneuv.so" 2>/dev/null | grep -q 'NEEDED.*libasan'; then
    echo "SKIP: $BUILD is a sanitizer build"; exit 77
fi
mkdir -p "${NEUV_TEST_TMP:-/tmp}"
TMP=$(mktemp -d "${NEUV_TEST_TMP:-/tmp}/cli_python.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
export PYTHONDONTWRITEBYTECODE=1  # no __pycache__ in the source tree

failed=0
# The package from the source tree on this build's library and CLI.
export NEUV_LIBRARY=$BUILD/libneuv.so NEUV_CLI=$NEUV
if ! PYTHONPATH=$SRC/python "$PY" -c '
import os, sys, neuv
want = os.path.realpath(os.environ["NEUV_LIBRARY"])
sys.exit(0 if neuv.library_path == want else "neuv loaded %s, not %s" % (neuv.library_path, want))'; then
    echo "FAIL: the package does not load $BUILD/libneuv.so"; failed=1
fi
if ! PYTHONPATH=$SRC/python "$PY" -m pytest -q -p no:cacheprovider --basetemp="$TMP/pytest" "$SRC/python/tests"; then
    echo "FAIL: python/tests"; failed=1
fi

# `make python`'s install, into a fresh venv; the package must then use its own copy of the library.
if ! "$PY" -c 'import ensurepip, venv' 2>/dev/null; then
    echo "SKIP (install check only): no venv/ensurepip for $PY (Debian: python3-venv)"
elif ! bash "$SRC/python/install.sh" "$TMP/venv" "$BUILD/libneuv.so" "$PY" >"$TMP/install.log" 2>&1; then
    cat "$TMP/install.log"; echo "FAIL: python/install.sh"; failed=1
elif ! (cd "$TMP" && env -u NEUV_LIBRARY "$TMP/venv/bin/python" -c '
import os, numpy as np, neuv
here = os.path.realpath(os.path.dirname(neuv.__file__))
assert here.startswith(os.path.realpath("venv") + os.sep), here
assert neuv.library_path == os.path.join(here, "libneuv.so"), neuv.library_path
V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
vmapping, indices, uvs = neuv.unwrap(V, [[0, 1, 2], [0, 2, 3]], method="lscm", iters=30, use_cache=False, resolution=64)
assert indices.shape == (2, 3) and (uvs >= 0).all() and (uvs <= 1).all()
print("installed package:", here)'); then
    echo "FAIL: the installed package"; failed=1
fi
[ -e "$SRC/python/build" ] && { echo "FAIL: the install left python/build behind"; failed=1; }
[ "$failed" -eq 0 ] && echo "cli_python: passed"
exit "$failed"
