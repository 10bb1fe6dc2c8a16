#!/usr/bin/env bash
# neuv flatten and neuv geodesics from the command line: disks flatten into a
# file with vt lines, other topologies fail with exit 2 and one line.
# Usage: bash tests/cli_flatten.sh /path/to/neuv
NEUV=${1:?usage: cli_flatten.sh /path/to/neuv}
SHARED=${NEUV_SHARED:-../shared}
TMP=${NEUV_TEST_TMP:-/tmp}/cli_flatten
mkdir -p "$TMP"
pass=0; fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }

if [ ! -f "$SHARED/meshes/grid.off" ]; then echo "SKIP: $SHARED/meshes absent"; exit 77; fi

for mesh in grid.off camelhead.off; do
  for method in lscm harmonic; do
    out="$TMP/${mesh%.*}-$method.obj"
    rm -f "$out"
    if "$NEUV" flatten "$SHARED/meshes/$mesh" --method "$method" -o "$out" --quiet > "$TMP/out.txt" 2> "$TMP/err.txt"; then ok; else bad "flatten $mesh $method exit $?: $(cat "$TMP/err.txt")"; fi
    nvt=$(grep -c '^vt ' "$out" 2>/dev/null)
    if [ "${nvt:-0}" -gt 0 ]; then ok; else bad "$out has no vt lines"; fi
    # The UVs were scaled into [0,1]^2.
    if awk '/^vt /{ if ($2 < 0 || $2 > 1 || $3 < 0 || $3 > 1) exit 1 }' "$out"; then ok; else bad "$out: vt outside [0,1]"; fi
    if grep -q 'flipped 0' "$TMP/out.txt"; then ok; else bad "flatten $mesh $method: $(cat "$TMP/out.txt")"; fi
  done
done

# Not a disk: exit 2, one line naming the topology.
"$NEUV" flatten "$SHARED/meshes/fertility.off" --method lscm -o "$TMP/fertility.obj" > /dev/null 2> "$TMP/err.txt"
rc=$?
if [ "$rc" -eq 2 ]; then ok; else bad "fertility: exit $rc, expected 2"; fi
if [ "$(wc -l < "$TMP/err.txt")" -eq 1 ] && grep -q 'not a disk: 1 component, closed, genus 4' "$TMP/err.txt"; then ok; else bad "fertility message: $(cat "$TMP/err.txt")"; fi
if [ ! -e "$TMP/fertility.obj" ]; then ok; else bad "fertility wrote an output"; fi

# Bad usage.
"$NEUV" flatten "$SHARED/meshes/grid.off" --method conformal -o "$TMP/x.obj" 2> /dev/null
rc=$?; if [ "$rc" -eq 2 ]; then ok; else bad "unknown method: exit $rc"; fi
"$NEUV" flatten "$SHARED/meshes/grid.off" --method lscm -o "$SHARED/meshes/grid.off" 2> /dev/null
rc=$?; if [ "$rc" -eq 2 ]; then ok; else bad "output onto input: exit $rc"; fi

# Geodesics: JSON with one distance per vertex, 0 at the source; bad source exit 2.
"$NEUV" geodesics "$SHARED/meshes/grid.off" --from 0 --json > "$TMP/geo.json" 2> "$TMP/err.txt"
rc=$?; if [ "$rc" -eq 0 ]; then ok; else bad "geodesics exit $rc: $(cat "$TMP/err.txt")"; fi
if python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert d["source"] == 0 and len(d["distances"]) == 145 and d["distances"][0] == 0
assert all(x is not None and x >= 0 for x in d["distances"]) and max(d["distances"]) > 0
' "$TMP/geo.json" 2>/dev/null; then ok; else bad "geodesics JSON: $(head -c 200 "$TMP/geo.json")"; fi
"$NEUV" geodesics "$SHARED/meshes/grid.off" --from 145 > /dev/null 2> "$TMP/err.txt"
rc=$?; if [ "$rc" -eq 2 ] && [ "$(wc -l < "$TMP/err.txt")" -eq 1 ]; then ok; else bad "geodesics bad source: exit $rc"; fi

echo "cli_flatten: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
