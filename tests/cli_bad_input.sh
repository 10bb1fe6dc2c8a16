#!/usr/bin/env bash
# Bad input through the CLI (SPEC.md section 7): each case must exit 2, print
# exactly one line on stderr, `neuv: error: FILE: message`, and leave no
# output file and no temporary behind. Run with `neuv convert`, and with
# `neuv info` when the binary has that command.
# Usage: cli_bad_input.sh /path/to/neuv
set -u
NEUV=${1:?usage: cli_bad_input.sh /path/to/neuv}
ROOT=${NEUV_TEST_TMP:-/tmp}/cli_bad_input
rm -rf "$ROOT"
mkdir -p "$ROOT"
D=$ROOT
pass=0
fail=0

ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# ---- the bad files ---------------------------------------------------------
mkdir -p "$D/folder.obj"
: > "$D/empty.obj"
printf '0 0 0\n1 0 0\n0 1 0\n' > "$D/points.xyz"
printf 'v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n' > "$D/nan.obj"
printf 'OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n' > "$D/inf.off"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 900\n' > "$D/range.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\n' > "$D/cloud.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$D/good.obj"
{
    printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\n'
    printf 'property float x\nproperty float y\nproperty float z\n'
    printf 'element face 2\nproperty list uchar int vertex_indices\nend_header\n'
    head -c 36 /dev/zero
    printf '\003\000\000\000\000\001\000\000\000\002\000\000\000'   # face 0; face 1 is missing
} > "$D/truncated.ply"

# glTF: a GLB cut short, a .gltf whose buffer file is missing, a .gltf that is not JSON.
printf 'glTF\002\000\000\000\000\020\000\000\024\000\000\000JSON{"asset":' > "$D/cut.glb"
printf '{"asset":{"version":"2.0"},"buffers":[{"byteLength":12,"uri":"gone.bin"}]}' > "$D/nobuffer.gltf"
printf '{"asset":{"version":"2.0"},,}' > "$D/notjson.gltf"

# check LABEL NAMED_FILE MESSAGE OUTPUT -- COMMAND...
# NAMED_FILE is the file the error line must name (the input, or the output
# when that is what is wrong); OUTPUT, when not empty, must not exist after
# the run, nor any temporary beside it.
check() {
    local label=$1 named=$2 msg=$3 out=$4
    shift 5
    local err rc lines
    err=$("$@" 2>&1 >/dev/null)
    rc=$?
    lines=$(printf '%s' "$err" | grep -c '')
    [ "$rc" -eq 2 ] && ok || bad "$label: exit code $rc, expected 2"
    [ "$lines" -eq 1 ] && ok || bad "$label: $lines lines on stderr, expected 1: $err"
    case "$err" in
        "neuv: error: $named: "*) ok ;;
        *) bad "$label: stderr does not start with 'neuv: error: $named: ': $err" ;;
    esac
    case "$err" in
        *"$msg"*) ok ;;
        *) bad "$label: message lacks '$msg': $err" ;;
    esac
    if [ -n "$out" ]; then
        [ ! -e "$out" ] && ok || bad "$label: output $out was written"
        if ls "$out".tmp-* >/dev/null 2>&1; then bad "$label: temporary file left: $(ls "$out".tmp-*)"; else ok; fi
    fi
}

declare -a NAMES INPUTS MSGS
add() { NAMES+=("$1"); INPUTS+=("$2"); MSGS+=("$3"); }
add missing   "$D/missing.obj"   "cannot open: No such file or directory"
add directory "$D/folder.obj"    "is a directory, not a mesh file"
add empty     "$D/empty.obj"     "empty file"
add unknown   "$D/points.xyz"    "unknown format '.xyz' (expected .obj, .off, .ply, .stl, .gltf, .glb)"
add truncated "$D/truncated.ply" "truncated: header declares 2 faces, data ends after 1"
add nan       "$D/nan.obj"       "non-finite coordinate"
add inf       "$D/inf.off"       "non-finite coordinate"
add range     "$D/range.obj"     "references vertex 900, but there are 3 vertices"
add nofaces   "$D/cloud.obj"     "no faces (a point cloud?); neuv needs a triangle mesh"
add cutglb    "$D/cut.glb"       "glTF: GLB header gives 4096 bytes, the file has 29"
add nobuffer  "$D/nobuffer.gltf" "glTF: buffer 0: cannot open 'gone.bin'"
add notjson   "$D/notjson.gltf"  "glTF: JSON: line 1: expected a key"

for i in "${!NAMES[@]}"; do
    out="$D/out-${NAMES[$i]}.obj"
    check "convert ${NAMES[$i]}" "${INPUTS[$i]}" "${MSGS[$i]}" "$out" -- "$NEUV" convert "${INPUTS[$i]}" -o "$out"
done

# The output is what is wrong.
out="$D/no-such-folder/out.obj"
check "convert missing output folder" "$out" "folder $D/no-such-folder does not exist" "$out" -- \
    "$NEUV" convert "$D/good.obj" -o "$out"
[ ! -e "$D/no-such-folder" ] && ok || bad "convert created the missing folder"
out="$D/out.xyz"
check "convert unknown output format" "$out" "unknown output format '.xyz'" "$out" -- \
    "$NEUV" convert "$D/good.obj" -o "$out"
cp "$D/good.obj" "$D/keep.obj"
check "convert onto its input" "$D/keep.obj" "overwrite the input" "" -- "$NEUV" convert "$D/keep.obj" -o "$D/keep.obj"
cmp -s "$D/good.obj" "$D/keep.obj" && ok || bad "convert onto its input changed the input"

# A good conversion still works and leaves only its output.
if "$NEUV" convert "$D/good.obj" -o "$D/good.ply" --quiet 2>"$D/stderr.txt"; then ok; else bad "convert good.obj failed: $(cat "$D/stderr.txt")"; fi
[ -s "$D/good.ply" ] && ok || bad "convert good.obj wrote no good.ply"
if ls "$D"/*.tmp-* >/dev/null 2>&1; then bad "temporary files left: $(ls "$D"/*.tmp-*)"; else ok; fi

# ---- the same inputs through neuv info, once it exists ---------------------
if "$NEUV" --help 2>/dev/null | grep -q ' info '; then
    for i in "${!NAMES[@]}"; do
        check "info ${NAMES[$i]}" "${INPUTS[$i]}" "${MSGS[$i]}" "" -- "$NEUV" info "${INPUTS[$i]}"
    done
else
    echo "neuv info not in this binary: its cases skipped"
fi

echo "cli_bad_input: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
