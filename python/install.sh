#!/usr/bin/env bash
# Installs the Python package with Debian's Python into a virtual environment:
# the venv (created once, with --system-site-packages so that Debian's NumPy
# serves), then pip without network or build isolation, Debian's setuptools
# building it and copying the library into the package.
# usage: python/install.sh VENV LIBNEUV_SO [PYTHON]   (`make python` runs it)
set -euo pipefail
VENV=${1:?usage: install.sh VENV LIBNEUV_SO [PYTHON]}
LIB=${2:?usage: install.sh VENV LIBNEUV_SO [PYTHON]}
PYTHON=${3:-/usr/bin/python3}
HERE=$(cd "$(dirname "$0")" && pwd)
[ -e "$LIB" ] || { echo "install.sh: no $LIB (build the library first)" >&2; exit 1; }
if [ ! -x "$VENV/bin/python" ]; then
    "$PYTHON" -m venv --system-site-packages "$VENV"
fi
# pip builds in place: the build/ and egg-info it leaves beside setup.py are
# removed, so that a later install copies the library afresh.
trap 'rm -rf "$HERE/build" "$HERE/neuv.egg-info"' EXIT
NEUV_LIBRARY=$(realpath "$LIB") "$VENV/bin/python" -m pip install --quiet --no-index --no-build-isolation \
    --no-deps --force-reinstall --disable-pip-version-check "$HERE"
"$VENV/bin/python" -c 'import neuv; print("neuv", neuv.__version__, "installed in", neuv.__file__.rsplit("/", 1)[0], "with", neuv.library_path)'
