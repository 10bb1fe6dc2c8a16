#!/usr/bin/env bash
# The Blender add-on (blender/neuv_addon) in a headless Blender: its
# operators on procedural meshes, checked against `neuv eval` on an OBJ
# export (blender/tests/check_addon.py says what is checked). Skips (77)
# without Blender (Debian: blender; make setup) or in a sanitizer build.
# usage: cli_blender.sh /path/to/build/neuv   (the build folder is its folder)
set -u
NEUV=${1:?usage: cli_blender.sh /path/to/build/neuv}
HERE=$(cd "$(dirname "$0")" && pwd)
SRC=$(cd "$HERE/.." && pwd)
BUILD=$(cd "$(dirname "$NEUV")" && pwd)
NEUV=$BUILD/$(basename "$NEUV")
BLENDER=${NEUV_BLENDER:-blender}
command -v "$BLENDER" >/dev/null 2>&1 || { echo "SKIP: no blender (Debian: blender; make setup)"; exit 77; }
[ -e "$BUILD/libneuv.so" ] || { echo "FAIL: no $BUILD/libneuv.so"; exit 1; }
# Blender's Python cannot load a library built with the ASan runtime.
if readelf -d "$BUILD/libneuv.so" 2>/dev/null | grep -q 'NEEDED.*libasan'; then
    echo "SKIP: $BUILD is a sanitizer build"; exit 77
fi
mkdir -p "${NEUV_TEST_TMP:-/tmp}"
TMP=$(mktemp -d "${NEUV_TEST_TMP:-/tmp}/cli_blender.XXXXXX")
trap 'rm -rf "$TMP"' EXIT

# A user scripts folder of our own: the add-on linked in, no user settings read.
mkdir -p "$TMP/scripts/addons" "$TMP/config"
ln -s "$SRC/blender/neuv_addon" "$TMP/scripts/addons/neuv_addon"
export BLENDER_USER_SCRIPTS=$TMP/scripts BLENDER_USER_CONFIG=$TMP/config
export NEUV_LIBRARY=$BUILD/libneuv.so OPENBLAS_NUM_THREADS=1 PYTHONDONTWRITEBYTECODE=1
unset NEUV_PYTHONPATH  # the add-on's preference is what the script sets

start=$(date +%s)
"$BLENDER" -b --factory-startup --python-exit-code 1 \
    --python "$SRC/blender/tests/check_addon.py" -- "$SRC" "$NEUV" "$TMP" >"$TMP/blender.log" 2>&1
rc=$?
grep -E '^(ok|FAIL|unwrap|qce_mean|check_addon|Info|Error|Traceback)|Error:' "$TMP/blender.log"
if [ "$rc" -ne 0 ] || ! grep -q '^check_addon: 0 failed' "$TMP/blender.log"; then
    tail -40 "$TMP/blender.log"
    echo "FAIL: blender exited with $rc"
    exit 1
fi
echo "cli_blender: passed in $(( $(date +%s) - start )) s"
