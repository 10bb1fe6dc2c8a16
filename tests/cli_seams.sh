#!/usr/bin/env bash
# Required seams from the command line, on OBJ files written here:
#  - a closed cylinder whose side has smooth normals and whose caps have
#    their own (hard edges at the two rims), the side and caps in two
#    materials: by default no chart crosses a rim; --no-hard-edges turns
#    that off; --save-model is refused while the file marks hard edges;
#  - a tube in two materials (no normals): the border between them is kept;
#  - the same cylinder flat shaded (every corner has its face's normal):
#    the normals are not taken (every edge would be hard), --seam-angle is.
# Each check reads the written OBJ: the two faces of a seam edge must have
# different UVs at one of its ends.
# Usage: bash tests/cli_seams.sh /path/to/neuv
set -u
NEUV=${1:?usage: cli_seams.sh /path/to/neuv}
TMP=${NEUV_TEST_TMP:-/tmp}/cli_seams
rm -rf "$TMP"; mkdir -p "$TMP"
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
pass=0; fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }

"$PY" - "$TMP" <<'PYEOF'
import math, sys
tmp = sys.argv[1]
A, R = 24, 6  # around, rows of the side

def cylinder(path, flat=False, materials=True, normals=True, caps=True):
    v, vn, faces = [], [], []  # faces: (material, [(v, vn)])
    for r in range(R + 1):
        for a in range(A):
            t = 2 * math.pi * a / A
            v.append((math.cos(t), math.sin(t), r / R * 2 - 1))
    for a in range(A):
        t = 2 * math.pi * a / A
        vn.append((math.cos(t), math.sin(t), 0))
    vn += [(0, 0, 1), (0, 0, -1)]
    for r in range(R):
        for a in range(A):
            i, j = r * A + a, r * A + (a + 1) % A
            k, l = i + A, j + A
            for tri in ((i, j, l), (i, l, k)):
                faces.append(("side", [(x, x % A) for x in tri]))
    if caps:
        top, bottom = len(v), len(v) + 1
        v += [(0, 0, 1), (0, 0, -1)]
        for a in range(A):
            i, j = R * A + a, R * A + (a + 1) % A
            faces.append(("cap", [(i, A), (j, A), (top, A)]))
            i, j = a, (a + 1) % A
            faces.append(("cap", [(j, A + 1), (i, A + 1), (bottom, A + 1)]))
    with open(path, "w") as f:
        if flat:
            vn = []
            for _, c in faces:
                p = [v[x] for x, _ in c]
                e1 = [p[1][i] - p[0][i] for i in range(3)]
                e2 = [p[2][i] - p[0][i] for i in range(3)]
                n = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
                vn.append(n)
            faces = [(m, [(x, i) for x, _ in c]) for i, (m, c) in enumerate(faces)]
        for p in v:
            f.write("v %.17g %.17g %.17g\n" % p)
        if normals:
            for n in vn:
                f.write("vn %.9g %.9g %.9g\n" % n)
        used = None
        for m, c in faces:
            if materials and m != used:
                f.write(f"usemtl {m}\n")
                used = m
            if normals:
                f.write("f " + " ".join(f"{x + 1}//{n + 1}" for x, n in c) + "\n")
            else:
                f.write("f " + " ".join(f"{x + 1}" for x, _ in c) + "\n")

cylinder(f"{tmp}/hard.obj", materials=False)
cylinder(f"{tmp}/flat.obj", flat=True, materials=False)
cylinder(f"{tmp}/mtl.obj", normals=False, caps=False)
# The tube with two materials: rows below the middle "a", above "b".
lines = open(f"{tmp}/mtl.obj").read().splitlines()
out, face = [], 0
for line in lines:
    if line.startswith("usemtl"):
        continue
    if line.startswith("f "):
        if face == 0:
            out.append("usemtl a")
        if face == A * R:  # two triangles per quad: half the rows
            out.append("usemtl b")
        face += 1
    out.append(line)
open(f"{tmp}/mtl.obj", "w").write("\n".join(out) + "\n")
PYEOF

# check NAME EXPR: the report NAME.json and OBJ NAME.obj; EXPR over r (report)
# and split(z) (for the edges of the unit ring at height z: how many have
# different UVs on their two faces, and how many there are).
check() {
  local name="$1" expr="$2"
  "$PY" - "$TMP" "$name" "$expr" <<'PYEOF' && ok || bad "$name: $expr"
import json, sys
tmp, name, expr = sys.argv[1:4]
r = json.load(open(f"{tmp}/{name}.json"))
V, T, F = [], [], []
for line in open(f"{tmp}/{name}.obj"):
    p = line.split()
    if not p: continue
    if p[0] == "v": V.append(tuple(float(x) for x in p[1:4]))
    elif p[0] == "vt": T.append(tuple(float(x) for x in p[1:3]))
    elif p[0] == "f": F.append([tuple(int(x) - 1 for x in c.split("/")[:2]) for c in p[1:]])
def split(z):
    edges = {}
    for f, c in enumerate(F):
        for k in range(3):
            a, b = c[k][0], c[(k + 1) % 3][0]
            on = [abs(V[x][2] - z) < 1e-9 and abs(V[x][0] ** 2 + V[x][1] ** 2 - 1) < 1e-9 for x in (a, b)]
            if all(on):
                edges.setdefault((min(a, b), max(a, b)), []).append(f)
    n = 0
    for (a, b), fs in edges.items():
        if len(fs) != 2: continue
        uv = [{x: T[t] for x, t in F[f]} for f in fs]
        n += uv[0][a] != uv[1][a] or uv[0][b] != uv[1][b]
    return n, len(edges)
if not eval(expr):
    print(f"  seams {r['seams']}, charts {r['charts']}, split(1) {split(1)}, split(-1) {split(-1)}, "
          f"split(0) {split(0)}", file=sys.stderr)
    sys.exit(1)
PYEOF
}

LSCM=(--method lscm --iters 20 --resolution 256 --threads 1 --quiet)
unwrap() { local name="$1" in="$2"; shift 2; "$NEUV" unwrap "$TMP/$in" -o "$TMP/$name.obj" --report "$TMP/$name.json" "${LSCM[@]}" "$@"; }

# Hard edges at the rims (24 each), by default: no chart crosses them.
unwrap hard-uv hard.obj || bad "unwrap hard.obj failed"
check hard-uv 'r["seams"]["from_normals"] == 48 == r["seams"]["required_edges"] and r["seams"]["crossed"] == 0 and split(1) == (24, 24) and split(-1) == (24, 24) and r["metrics"]["flipped"] == 0 and r["metrics"]["overlap_fraction"] == 0'
# Without them the charts are PatchNet's alone: a rim is crossed somewhere.
unwrap soft hard.obj --no-hard-edges --charts 2 || bad "unwrap --no-hard-edges failed"
check soft 'r["seams"]["required_edges"] == 0 and not r["seams"]["hard_edges"] and (split(1)[0] < 24 or split(-1)[0] < 24)'
# A model to save would not record them: refused, and nothing written.
"$NEUV" unwrap "$TMP/hard.obj" -o "$TMP/saved.obj" --save-model "$TMP/m.neuv" "${LSCM[@]}" 2>"$TMP/save.err"
rc=$?
[ $rc -eq 2 ] && grep -q "no-hard-edges" "$TMP/save.err" && [ ! -e "$TMP/saved.obj" ] && [ ! -e "$TMP/m.neuv" ] && ok \
  || bad "--save-model with hard edges: rc=$rc $(cat "$TMP/save.err")"

# Two materials meet at the tube's middle ring (24 edges, no normals).
unwrap mtl-uv mtl.obj --charts 1 || bad "unwrap mtl.obj failed"
check mtl-uv 'r["seams"]["from_materials"] == 24 == r["seams"]["required_edges"] and r["seams"]["crossed"] == 0 and split(0) == (24, 24)'

# Flat shading marks every edge: the normals are not taken; --seam-angle is.
unwrap flat-uv flat.obj || bad "unwrap flat.obj failed"
check flat-uv 'r["seams"]["flat_shaded"] and r["seams"]["required_edges"] == 0'
unwrap flat60 flat.obj --seam-angle 60 || bad "unwrap flat.obj --seam-angle 60 failed"
check flat60 'r["seams"]["above_angle"] == 48 and r["seams"]["crossed"] == 0 and split(1) == (24, 24) and split(-1) == (24, 24)'

echo "cli_seams: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
