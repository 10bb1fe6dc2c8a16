#!/usr/bin/env bash
# neuv remesh and neuv compare: face counts of simplified and subdivided
# spot.obj, isotropic remeshing towards a face count or an edge length,
# a file compared with itself and with its jittered subdivision, JSON keys,
# and one-line errors with exit code 2.
# usage: cli_remesh.sh /path/to/neuv
set -u
NEUV=${1:?usage: cli_remesh.sh /path/to/neuv}
HERE=$(cd "$(dirname "$0")" && pwd)
MESHES=${NEUV_SHARED:-$HERE/../../shared}/meshes
TMP=${NEUV_TEST_TMP:-/tmp}/cli_remesh.$$
mkdir -p "$TMP"
trap 'rm -rf "$TMP"' EXIT

passed=0 failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }

# faces FILE: the number of faces (lines starting with "f ") of an OBJ.
faces() { grep -c '^f ' "$1"; }

# expect_error ARGS...: exit code 2 and a single line on stderr.
expect_error() {
    "$NEUV" "$@" >"$TMP/out" 2>"$TMP/err"
    local rc=$? lines
    lines=$(wc -l <"$TMP/err")
    if [ "$rc" -eq 2 ] && [ "$lines" -eq 1 ]; then ok; else bad "neuv $* -> rc $rc, stderr: $(cat "$TMP/err")"; fi
}

# A procedural-free fixture: a 4x4 grid with identity UVs written by hand.
python3 - "$TMP/grid.obj" <<'EOF2' 2>/dev/null || printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n' >"$TMP/grid.obj"
import sys
n = 4
with open(sys.argv[1], "w") as f:
    for j in range(n + 1):
        for i in range(n + 1):
            f.write(f"v {i / n} {j / n} 0\n")
    for j in range(n + 1):
        for i in range(n + 1):
            f.write(f"vt {i / n} {j / n}\n")
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            b, c, d = a + 1, a + n + 2, a + n + 1
            f.write(f"f {a}/{a} {b}/{b} {c}/{c}\nf {a}/{a} {c}/{c} {d}/{d}\n")
EOF2
GF=$(faces "$TMP/grid.obj")

# Local fixture: subdivision counts, compare with itself and with a jittered subdivision.
if "$NEUV" remesh "$TMP/grid.obj" -o "$TMP/g2.obj" --subdivide 2 --quiet >/dev/null 2>"$TMP/err" &&
   [ "$(faces "$TMP/g2.obj")" -eq $((GF * 16)) ]; then ok; else bad "grid --subdivide 2: $(cat "$TMP/err")"; fi
out=$("$NEUV" remesh "$TMP/grid.obj" -o "$TMP/gq.obj" --subdivide 1 --jitter --quiet 2>&1)
if [ $? -eq 0 ] && [ -z "$out" ] && [ -s "$TMP/gq.obj" ]; then ok; else bad "remesh --quiet printed: $out"; fi
if "$NEUV" remesh "$TMP/grid.obj" -o "$TMP/gl.obj" --subdivide 1 --loop >/dev/null 2>"$TMP/err" &&
   [ "$(faces "$TMP/gl.obj")" -eq $((GF * 4)) ]; then ok; else bad "grid --subdivide 1 --loop: $(cat "$TMP/err")"; fi
if "$NEUV" remesh "$TMP/grid.obj" -o "$TMP/gj.obj" --subdivide 1 --jitter --seed 3 >/dev/null 2>"$TMP/err" &&
   [ "$(faces "$TMP/gj.obj")" -eq $((GF * 4)) ] && ! cmp -s "$TMP/gj.obj" "$TMP/g2.obj"; then ok; else bad "grid jitter: $(cat "$TMP/err")"; fi
# Same seed, same file.
"$NEUV" remesh "$TMP/grid.obj" -o "$TMP/gj2.obj" --subdivide 1 --jitter --seed 3 >/dev/null 2>&1
if cmp -s "$TMP/gj.obj" "$TMP/gj2.obj"; then ok; else bad "jitter not deterministic for a seed"; fi
if command -v python3 >/dev/null; then
    # cmp_json FILE_A FILE_B PYTHON_CONDITION on the parsed JSON `j`.
    cmp_json() {
        if ! "$NEUV" compare "$1" "$2" --json >"$TMP/c.json" 2>"$TMP/err"; then bad "compare $1 $2: $(cat "$TMP/err")"; return; fi
        if python3 - "$TMP/c.json" "$3" <<'EOF2'
import json, sys
j = json.load(open(sys.argv[1]))
for key in ("uv_distance", "chart_agreement", "faces_a", "faces_b", "vertices_compared"):
    assert key in j, key
for key in ("mean", "p95", "max"):
    assert key in j["uv_distance"], key
if not eval(sys.argv[2]):
    print(json.dumps(j)); sys.exit(1)
EOF2
        then ok; else bad "compare $(basename "$1") $(basename "$2"): expected $3"; fi
    }
    cmp_json "$TMP/grid.obj" "$TMP/grid.obj" 'j["uv_distance"]["max"] == 0 and j["chart_agreement"] == 1'
    cmp_json "$TMP/grid.obj" "$TMP/gj.obj" 'j["uv_distance"]["max"] < 1e-9 and j["chart_agreement"] == 1 and j["faces_b"] == 4 * j["faces_a"]'
fi
if "$NEUV" compare "$TMP/grid.obj" "$TMP/grid.obj" >"$TMP/out" 2>&1 && grep -q "mean 0 " "$TMP/out"; then ok; else bad "compare text: $(cat "$TMP/out")"; fi

# Isotropic remeshing of a built-in shape: the face count near the target,
# the summary line, --jitter after it, and an edge length on the flat grid.
if "$NEUV" shape cube -o "$TMP/cube.obj" >/dev/null 2>"$TMP/err"; then
    if "$NEUV" remesh "$TMP/cube.obj" -o "$TMP/cube_iso.obj" --faces 1000 >"$TMP/out" 2>"$TMP/err"; then
        n=$(faces "$TMP/cube_iso.obj")
        if [ "$n" -ge 750 ] && [ "$n" -le 1250 ] && grep -q "isotropic: 3072 -> $n faces (target 1000" "$TMP/out" &&
           grep -q "feature edges kept" "$TMP/out" && grep -q "max distance to the input" "$TMP/out"; then ok
        else bad "cube --faces 1000: $n faces, $(cat "$TMP/out")"; fi
    else bad "cube --faces 1000: $(cat "$TMP/err")"; fi
    if "$NEUV" remesh "$TMP/cube.obj" -o "$TMP/cube_isoj.obj" --faces 1000 --jitter >"$TMP/out" 2>"$TMP/err" &&
       [ "$(faces "$TMP/cube_isoj.obj")" -eq "$(faces "$TMP/cube_iso.obj")" ] && grep -q "jitter" "$TMP/out" &&
       ! cmp -s "$TMP/cube_iso.obj" "$TMP/cube_isoj.obj"; then ok
    else bad "cube --faces 1000 --jitter: $(cat "$TMP/err")"; fi
else bad "neuv shape cube: $(cat "$TMP/err")"; fi
if "$NEUV" remesh "$TMP/grid.obj" -o "$TMP/g_iso.obj" --isotropic 0.1 >"$TMP/out" 2>"$TMP/err" &&
   [ "$(faces "$TMP/g_iso.obj")" -gt $((GF * 4)) ] && ! grep -q '^vt ' "$TMP/g_iso.obj"; then ok
else bad "grid --isotropic 0.1: $(cat "$TMP/err")"; fi

# Errors: one line, exit 2.
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --isotropic -1
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --isotropic 0
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --isotropic abc
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --isotropic 0.1 --faces 100
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --faces 3
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --faces 1.5
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --faces 100 --subdivide 1
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --isotropic 1e-9
# A Moebius strip survives cleaning (left as it is, with a warning) but has
# no orientation for the remesher: exit 2, the error names it.
printf '%s\n' 'v 0.7 0 0' 'v 1.3 0 0' 'v 0.3701 0.641 -0.15' 'v 0.6299 1.091 0.15' 'v -0.425 0.7361 -0.2598' \
    'v -0.575 0.9959 0.2598' 'v -1 0 -0.3' 'v -1 0 0.3' 'v -0.575 -0.9959 -0.2598' 'v -0.425 -0.7361 0.2598' \
    'v 0.6299 -1.091 -0.15' 'v 0.3701 -0.641 0.15' 'f 1 3 4' 'f 1 4 2' 'f 3 5 6' 'f 3 6 4' 'f 5 7 8' 'f 5 8 6' \
    'f 7 9 10' 'f 7 10 8' 'f 9 11 12' 'f 9 12 10' 'f 11 2 1' 'f 11 1 12' >"$TMP/moebius.obj"
"$NEUV" remesh "$TMP/moebius.obj" -o "$TMP/x.obj" --faces 100 >/dev/null 2>"$TMP/err"
rc=$?
if [ "$rc" -eq 2 ] && [ "$(grep -c 'error:' "$TMP/err")" -eq 1 ] && grep -q "Moebius" "$TMP/err"; then ok
else bad "moebius --faces 100 -> rc $rc, stderr: $(cat "$TMP/err")"; fi
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --simplify 0
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --simplify 1.5
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --subdivide 0
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --subdivide 6
expect_error remesh "$TMP/grid.obj" --subdivide 1
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj"
expect_error remesh "$TMP/grid.obj" -o "$TMP/x.obj" --simplify abc
expect_error remesh "$TMP/grid.obj" -o "$TMP/grid.obj" --subdivide 1
expect_error remesh "$TMP/missing.obj" -o "$TMP/x.obj" --subdivide 1
expect_error compare "$TMP/grid.obj"
expect_error compare "$TMP/grid.obj" "$TMP/missing.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$TMP/nouv.obj"
expect_error compare "$TMP/grid.obj" "$TMP/nouv.obj"

# Shared meshes.
if [ -f "$MESHES/spot.obj" ]; then
    SF=$(faces "$MESHES/spot.obj")
    if "$NEUV" remesh "$MESHES/spot.obj" -o "$TMP/spot50.obj" --simplify 0.5 >/dev/null 2>"$TMP/err"; then
        n=$(faces "$TMP/spot50.obj")
        if [ "$n" -ge $((SF * 45 / 100)) ] && [ "$n" -le $((SF * 55 / 100)) ]; then ok; else bad "spot --simplify 0.5: $n faces of $SF"; fi
    else bad "spot --simplify 0.5: $(cat "$TMP/err")"; fi
    if "$NEUV" remesh "$MESHES/spot.obj" -o "$TMP/spotj.obj" --subdivide 1 --jitter >/dev/null 2>"$TMP/err" &&
       [ "$(faces "$TMP/spotj.obj")" -eq $((SF * 4)) ]; then ok; else bad "spot --subdivide 1 --jitter: $(cat "$TMP/err")"; fi
    if "$NEUV" remesh "$MESHES/spot.obj" -o "$TMP/spot_iso.obj" --faces $((SF * 2)) >/dev/null 2>"$TMP/err"; then
        n=$(faces "$TMP/spot_iso.obj")
        if [ "$n" -ge $((SF * 2 * 90 / 100)) ] && [ "$n" -le $((SF * 2 * 110 / 100)) ]; then ok; else bad "spot --faces $((SF * 2)): $n faces"; fi
    else bad "spot --faces $((SF * 2)): $(cat "$TMP/err")"; fi
    if "$NEUV" compare "$MESHES/spot.obj" "$MESHES/spot.obj" >"$TMP/out" 2>&1 && grep -q "mean 0 " "$TMP/out"; then ok
    else bad "spot compared with itself: $(cat "$TMP/out")"; fi
    if command -v python3 >/dev/null; then
        cmp_json "$MESHES/spot.obj" "$TMP/spotj.obj" 'j["uv_distance"]["max"] < 1e-9 and j["chart_agreement"] > 0.999'
        cmp_json "$MESHES/spot.obj" "$TMP/spot50.obj" 'j["uv_distance"]["max"] < 1e-9 and j["chart_agreement"] > 0.99'
    fi
else
    echo "SKIP (shared parts): no $MESHES"
fi

echo "cli_remesh: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
