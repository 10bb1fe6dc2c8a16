#!/usr/bin/env bash
# neuv segment from the command line: chart ids per face as a PLY face
# property `chart` or OBJ groups, the charts picture, JSON output, and bad
# arguments refused with exit 2.
# Usage: bash tests/cli_segment.sh /path/to/neuv
NEUV=${1:?usage: cli_segment.sh /path/to/neuv}
SHARED=${NEUV_SHARED:-../shared}
TMP=${NEUV_TEST_TMP:-/tmp}/cli_segment
mkdir -p "$TMP"
pass=0; fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }

# A procedural input: an octahedron (8 faces), written here.
cat > "$TMP/octa.obj" <<'OBJ'
v 1 0 0
v -1 0 0
v 0 1 0
v 0 -1 0
v 0 0 1
v 0 0 -1
f 1 3 5
f 3 2 5
f 2 4 5
f 4 1 5
f 3 1 6
f 2 3 6
f 4 2 6
f 1 4 6
OBJ
inputs="$TMP/octa.obj"
[ -f "$SHARED/meshes/woody.obj" ] && inputs="$inputs $SHARED/meshes/woody.obj"

for in in $inputs; do
  base=$(basename "${in%.*}")
  out="$TMP/$base-charts.ply"
  rm -f "$out" "$TMP/$base-charts.png"
  if "$NEUV" segment "$in" -o "$out" --iters 60 --preview "$TMP/$base" --quiet > "$TMP/out.txt" 2> "$TMP/err.txt"; then ok
  else bad "segment $base exit $?: $(cat "$TMP/err.txt")"; fi
  if grep -qa '^property int chart$' "$out" 2>/dev/null; then ok; else bad "$out has no face property chart"; fi
  # Every face line carries a chart id in 0..charts-1 as its fifth number.
  nf=$(awk '/^element face/{print $3}' "$out" 2>/dev/null)
  charts=$(sed -n 's/.*-> \([0-9]*\) charts.*/\1/p' "$TMP/out.txt")
  if [ -n "$nf" ] && [ -n "$charts" ] && awk -v nf="$nf" -v k="$charts" '
      /^end_header/ { body = 1; next }
      body && NF == 5 && $1 == 3 { n++; if ($5 < 0 || $5 >= k) badid++; seen[$5] = 1 }
      END { c = 0; for (s in seen) c++; exit !(n == nf && !badid && c == k) }' "$out"; then ok
  else bad "$out: chart ids do not cover 0..$charts-1 over $nf faces"; fi
  if [ -s "$TMP/$base-charts.png" ]; then ok; else bad "no preview $TMP/$base-charts.png"; fi
done

# OBJ output: one g chart_N group per chart; JSON report.
if "$NEUV" segment "$TMP/octa.obj" -o "$TMP/octa-groups.obj" --iters 30 --charts 4 --json --quiet > "$TMP/out.json" 2> "$TMP/err.txt"; then ok
else bad "segment obj exit $?: $(cat "$TMP/err.txt")"; fi
ng=$(grep -c '^g chart_' "$TMP/octa-groups.obj" 2>/dev/null)
nc=$(sed -n 's/.*"charts":\([0-9]*\).*/\1/p' "$TMP/out.json")
if [ "${ng:-0}" -ge 1 ] && [ "$ng" = "$nc" ]; then ok; else bad "OBJ groups $ng vs charts $nc"; fi
if [ "$(grep -c '^f ' "$TMP/octa-groups.obj")" = 8 ]; then ok; else bad "OBJ output lost faces"; fi

# Bad arguments: exit 2 with one line.
for args in "--charts 0" "--charts many" "--features normals" "--max-distortion 0.5"; do
  "$NEUV" segment "$TMP/octa.obj" -o "$TMP/x.ply" $args > /dev/null 2> "$TMP/err.txt"
  rc=$?
  if [ $rc = 2 ] && [ "$(wc -l < "$TMP/err.txt")" = 1 ]; then ok; else bad "segment $args: exit $rc, $(cat "$TMP/err.txt")"; fi
done
"$NEUV" segment "$TMP/octa.obj" -o "$TMP/x.stl" > /dev/null 2>&1
if [ $? = 2 ]; then ok; else bad "unknown output extension accepted"; fi
"$NEUV" segment "$TMP/missing.obj" -o "$TMP/x.ply" > /dev/null 2>&1
if [ $? = 2 ]; then ok; else bad "missing input not exit 2"; fi

echo "cli_segment: $pass passed, $fail failed"
[ $fail = 0 ]
