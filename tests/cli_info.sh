#!/usr/bin/env bash
# neuv info: topology of the shared meshes as JSON (components, genus,
# boundary loops), the repairs reported on a hand-written broken OFF, the
# text output, and one-line errors with exit code 2.
# usage: cli_info.sh /path/to/neuv
set -u
NEUV=${1:?usage: cli_info.sh /path/to/neuv}
HERE=$(cd "$(dirname "$0")" && pwd)
MESHES=${NEUV_SHARED:-$HERE/../../shared}/meshes
TMP=${NEUV_TEST_TMP:-/tmp}/cli_info.$$
if [ ! -d "$MESHES" ]; then echo "SKIP: no $MESHES"; exit 77; fi
if ! command -v python3 >/dev/null; then echo "SKIP: no python3"; exit 77; fi
mkdir -p "$TMP"
trap 'rm -rf "$TMP"' EXIT

passed=0 failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }

# check FILE PYTHON_CONDITION: runs `neuv info FILE --json`, then asserts
# the condition on the parsed object `j` (components in `c`).
check() {
    local file=$1 cond=$2 name
    name=$(basename "$file")
    if ! "$NEUV" info "$file" --json >"$TMP/out.json" 2>"$TMP/err"; then
        bad "$name: neuv info failed: $(cat "$TMP/err")"; return
    fi
    if python3 - "$TMP/out.json" "$cond" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
c = j["components"]
for key in ("input", "vertices", "faces", "components", "repairs", "has_uv", "input_vertices", "input_faces"):
    assert key in j, key
for key in ("welded_vertices", "degenerate_faces", "duplicate_faces", "unreferenced_vertices",
            "flipped_faces", "nonmanifold_edges", "nonmanifold_vertices", "split_vertices"):
    assert key in j["repairs"], key
for comp in c:
    assert comp["euler"] == comp["vertices"] - comp["edges"] + comp["faces"]
    assert comp["closed"] == (comp["boundary_loops"] == 0)
assert sum(comp["faces"] for comp in c) == j["faces"]
if not eval(sys.argv[2]):
    print(json.dumps(j)[:600])
    sys.exit(1)
EOF
    then ok; else bad "$name: expected $cond"; fi
}

check "$MESHES/fertility.off" 'len(c) == 1 and c[0]["closed"] and c[0]["genus"] == 4 and c[0]["euler"] == -6'
check "$MESHES/camelhead.off" 'len(c) == 1 and c[0]["boundary_loops"] == 1 and c[0]["genus"] == 0 and c[0]["euler"] == 1'
check "$MESHES/spot.obj" 'len(c) == 1 and c[0]["closed"] and c[0]["genus"] == 0 and j["has_uv"] and j["vertices"] == 2930 and j["faces"] == 5856'
check "$MESHES/3holes.off" 'len(c) == 1 and c[0]["closed"] and c[0]["genus"] == 3'
check "$MESHES/grid.off" 'len(c) == 1 and c[0]["boundary_loops"] == 1 and not j["has_uv"] and j["vertices"] == 145'
check "$MESHES/stanford-bunny.obj" 'len(c) == 1 and c[0]["boundary_loops"] == 5 and j["repairs"]["unreferenced_vertices"] == j["input_vertices"] - j["vertices"]'

# A broken OFF: a tetrahedron with one face flipped and one face twice,
# a degenerate face, an unused vertex, three triangles on one edge and a
# bow-tie vertex.
cat >"$TMP/broken.off" <<'EOF'
OFF
16 12 0
0 0 0
1 0 0
0 1 0
0 0 1
9 9 9
5 0 0
5 1 0
6 0.5 0
4 0.5 0
5 0.5 1
10 0 0
11 0 0
11 1 0
9 0 0
9 -1 0
0 0 0
3 0 2 1
3 0 1 3
3 1 2 3
3 2 3 0
3 3 1 0
3 0 1 15
3 5 6 7
3 6 5 8
3 5 6 9
3 10 11 12
3 10 13 14
3 0 1 2
EOF
check "$TMP/broken.off" 'j["repairs"] == {"welded_vertices": 1, "degenerate_faces": 1, "duplicate_faces": 2, "unreferenced_vertices": 1, "flipped_faces": 1, "nonmanifold_edges": 1, "nonmanifold_vertices": 1, "split_vertices": 3, "nonorientable_components": 0} and len(c) == 5 and c[0]["closed"] and c[0]["genus"] == 0'

# Text output: one summary line, the component table, the repairs.
if "$NEUV" info "$TMP/broken.off" >"$TMP/text" 2>"$TMP/err" &&
   head -1 "$TMP/text" | grep -q "broken.off: 17 vertices, 9 faces, 5 components, no UVs" &&
   grep -q "1 non-manifold edges split" "$TMP/text" &&
   grep -q "component" "$TMP/text"; then ok; else bad "text output: $(cat "$TMP/text" "$TMP/err")"; fi

# Errors: one line on stderr, exit code 2, nothing on stdout.
expect_error() {
    local what=$1; shift
    "$NEUV" info "$@" >"$TMP/out" 2>"$TMP/err"
    local rc=$?
    if [ "$rc" -eq 2 ] && [ "$(wc -l <"$TMP/err")" -eq 1 ] && [ ! -s "$TMP/out" ] &&
       grep -q "^neuv: error: " "$TMP/err"; then ok
    else bad "$what: rc=$rc stderr=$(cat "$TMP/err")"; fi
}
expect_error "missing file" "$TMP/does-not-exist.obj"
expect_error "no argument"
expect_error "unknown option" "$MESHES/grid.off" --frobnicate
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n' >"$TMP/range.off"
expect_error "index out of range" "$TMP/range.off"

echo "cli_info: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
