#!/usr/bin/env bash
# What comes in goes out (issue 19, item 1), on OBJ files written here:
#  - a closed quad cylinder with smooth side normals and hard caps, two
#    materials (side, caps), two groups (an object with groups "side" and
#    "caps"), vertex colours and an mtllib: the unwrapped OBJ has the same
#    vertices (positions and colours) in the same order, every quad as the
#    same quad, the same material, group and normal per face and corner,
#    the mtllib, and the new UVs;
#  - a quad torus unwrapped by the networks: no quad is split between
#    charts (the report's polygons.split is 0, every face of the output a
#    quad), with the chart borders that PatchNet drew moved onto quad edges;
#  - --uv-channel 1 is refused for OBJ output (one UV set) and for a file
#    without UVs, with exit 2.
# Usage: bash tests/cli_keep_file.sh /path/to/neuv
set -u
NEUV=${1:?usage: cli_keep_file.sh /path/to/neuv}
TMP=${NEUV_TEST_TMP:-/tmp}/cli_keep_file
rm -rf "$TMP"; mkdir -p "$TMP"
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
pass=0; fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }

"$PY" - "$TMP" <<'PYEOF'
import math, sys
tmp = sys.argv[1]

def quad_cylinder(path, A=16, R=4):
    """Side quads with smooth normals; each cap made of quads fanned to a
    centre vertex, with the cap's normal (hard rims)."""
    lines = ["mtllib parts.mtl"]
    v = []
    for r in range(R + 1):
        for a in range(A):
            t = 2 * math.pi * a / A
            v.append((math.cos(t), math.sin(t), r / R * 2 - 1))
    v += [(0, 0, 1), (0, 0, -1)]
    for i, p in enumerate(v):
        col = ((i % 7) / 7, (i % 5) / 5, (i % 3) / 3)
        lines.append("v %.17g %.17g %.17g %.6g %.6g %.6g" % (p + col))
    for a in range(A):
        t = 2 * math.pi * a / A
        lines.append("vn %.9g %.9g 0" % (math.cos(t), math.sin(t)))
    lines += ["vn 0 0 1", "vn 0 0 -1"]
    lines += ["o part", "g side", "usemtl metal", "s 1"]
    for r in range(R):
        for a in range(A):
            i, j = r * A + a, r * A + (a + 1) % A
            k, l = i + A, j + A
            lines.append("f " + " ".join(f"{x + 1}//{x % A + 1}" for x in (i, j, l, k)))
    top, bottom = len(v) - 2, len(v) - 1
    lines += ["g caps", "usemtl paint", "s off"]
    for a in range(0, A, 2):  # quads to the centre: (rim a, rim a+1, rim a+2, centre)
        i, j, k = R * A + a, R * A + (a + 1) % A, R * A + (a + 2) % A
        lines.append("f " + " ".join(f"{x + 1}//{A + 1}" for x in (i, j, k, top)))
        i, j, k = a, (a + 1) % A, (a + 2) % A
        lines.append("f " + " ".join(f"{x + 1}//{A + 2}" for x in (k, j, i, bottom)))
    open(path, "w").write("\n".join(lines) + "\n")

def quad_torus(path, n=32, m=12, R=1.0, r=0.4):
    lines = []
    for i in range(n):
        for j in range(m):
            u, w = 2 * math.pi * i / n, 2 * math.pi * j / m
            lines.append("v %.17g %.17g %.17g" % ((R + r * math.cos(w)) * math.cos(u),
                                                   (R + r * math.cos(w)) * math.sin(u), r * math.sin(w)))
    for i in range(n):
        for j in range(m):
            a, b = i * m + j, ((i + 1) % n) * m + j
            c, d = ((i + 1) % n) * m + (j + 1) % m, i * m + (j + 1) % m
            lines.append(f"f {a + 1} {b + 1} {c + 1} {d + 1}")
    open(path, "w").write("\n".join(lines) + "\n")

quad_cylinder(f"{tmp}/parts.obj")
quad_torus(f"{tmp}/torus.obj")
PYEOF

# An OBJ as a list of statements: vertices, the faces with their state.
cat > "$TMP/objparse.py" <<'PYEOF'
def read(path):
    v, vt, vn, faces = [], [], [], []
    state = {"o": None, "g": None, "s": None, "usemtl": None}
    mtllib = None
    for line in open(path):
        w = line.split()
        if not w or w[0].startswith("#"):
            continue
        if w[0] == "v":
            v.append(tuple(float(x) for x in w[1:]))
        elif w[0] == "vt":
            vt.append(tuple(float(x) for x in w[1:3]))
        elif w[0] == "vn":
            vn.append(tuple(float(x) for x in w[1:4]))
        elif w[0] in state:
            state[w[0]] = " ".join(w[1:])
        elif w[0] == "mtllib":
            mtllib = " ".join(w[1:])
        elif w[0] == "f":
            corners = []
            for c in w[1:]:
                p = c.split("/") + ["", ""]
                corners.append((int(p[0]) - 1, int(p[1]) - 1 if p[1] else None, int(p[2]) - 1 if p[2] else None))
            faces.append((dict(state), corners))
    return {"v": v, "vt": vt, "vn": vn, "faces": faces, "mtllib": mtllib}
PYEOF

# 1. The parts cylinder through the classic method (the file is what is checked).
"$NEUV" unwrap "$TMP/parts.obj" -o "$TMP/parts-uv.obj" --method lscm --report "$TMP/parts.json" --quiet \
    2>"$TMP/parts.err"
rc=$?
if [ $rc -ne 0 ]; then bad "unwrap parts.obj exit $rc: $(cat "$TMP/parts.err")"; else
out=$("$PY" - "$TMP" <<'PYEOF'
import sys, json
sys.path.insert(0, sys.argv[1])
import objparse
tmp = sys.argv[1]
a, b = objparse.read(f"{tmp}/parts.obj"), objparse.read(f"{tmp}/parts-uv.obj")
problems = []
if a["v"] != b["v"]:
    problems.append("vertices (positions and colours) differ")
if len(a["faces"]) != len(b["faces"]):
    problems.append(f"{len(a['faces'])} faces in, {len(b['faces'])} out")
if b["mtllib"] != "parts.mtl":
    problems.append(f"mtllib {b['mtllib']!r}")
for i, ((sa, ca), (sb, cb)) in enumerate(zip(a["faces"], b["faces"])):
    if sa != sb:
        problems.append(f"face {i}: state {sa} became {sb}")
    if [c[0] for c in ca] != [c[0] for c in cb]:
        problems.append(f"face {i}: vertices {[c[0] for c in ca]} became {[c[0] for c in cb]}")
    if [a["vn"][c[2]] for c in ca] != [b["vn"][c[2]] for c in cb]:
        problems.append(f"face {i}: normals differ")
    if any(c[1] is None for c in cb):
        problems.append(f"face {i}: a corner without UV")
# The UVs are the atlas's: inside the unit square, and the two parts' UVs
# differ at a rim vertex (a hard edge and a material border).
uvs = [b["vt"][c[1]] for _, cb in b["faces"] for c in cb if c[1] is not None]
if not uvs or min(min(u) for u in uvs) < 0 or max(max(u) for u in uvs) > 1:
    problems.append("UVs outside the unit square")
groups = {s["g"] for s, _ in b["faces"]}
materials = {s["usemtl"] for s, _ in b["faces"]}
if groups != {"side", "caps"} or materials != {"metal", "paint"}:
    problems.append(f"groups {groups}, materials {materials}")
rep = json.load(open(f"{tmp}/parts.json"))
if rep["polygons"] != {"input": len(a["faces"]), "split": 0}:
    problems.append(f"report polygons {rep['polygons']}")
if rep["metrics"]["flipped"] != 0 or rep["metrics"]["overlap_fraction"] != 0:
    problems.append("flips or overlap")
print("; ".join(problems[:5]) if problems else "ok")
PYEOF
)
[ "$out" = ok ] && ok || bad "parts.obj round trip: $out"
fi

# 2. The quad torus through the networks: every quad stays a quad.
"$NEUV" unwrap "$TMP/torus.obj" -o "$TMP/torus-uv.obj" --report "$TMP/torus.json" --quiet 2>"$TMP/torus.err"
rc=$?
if [ $rc -ne 0 ]; then bad "unwrap torus.obj exit $rc: $(cat "$TMP/torus.err")"; else
out=$("$PY" - "$TMP" <<'PYEOF'
import sys, json
sys.path.insert(0, sys.argv[1])
import objparse
tmp = sys.argv[1]
a, b = objparse.read(f"{tmp}/torus.obj"), objparse.read(f"{tmp}/torus-uv.obj")
rep = json.load(open(f"{tmp}/torus.json"))
problems = []
sizes = {len(c) for _, c in b["faces"]}
if sizes != {4} or len(b["faces"]) != len(a["faces"]):
    problems.append(f"{len(b['faces'])} faces of sizes {sizes}")
if [[c[0] for c in f] for _, f in a["faces"]] != [[c[0] for c in f] for _, f in b["faces"]]:
    problems.append("faces differ")
if rep["polygons"]["split"] != 0 or rep["polygons"]["input"] != len(a["faces"]):
    problems.append(f"report polygons {rep['polygons']}")
if rep["charts"] < 2:
    problems.append(f"{rep['charts']} chart(s): a torus needs cuts, so the test would not test")
if rep["metrics"]["flipped"] != 0 or rep["metrics"]["overlap_fraction"] != 0:
    problems.append("flips or overlap")
print("; ".join(problems[:5]) if problems else "ok")
PYEOF
)
[ "$out" = ok ] && ok || bad "torus.obj quads: $out"
fi

# 3. --uv-channel 1 where it cannot be honoured: exit 2, one line.
for args in "$TMP/parts-uv.obj -o $TMP/x.obj --uv-channel 1" "$TMP/parts.obj -o $TMP/x.ply --uv-channel 1" \
            "$TMP/parts.obj -o $TMP/x.ply --uv-channel 2"; do
    # shellcheck disable=SC2086
    "$NEUV" unwrap $args --method lscm --quiet >"$TMP/out.txt" 2>"$TMP/err.txt"
    rc=$?
    if [ $rc -eq 2 ] && [ "$(wc -l <"$TMP/err.txt")" -eq 1 ] && [ ! -e "$TMP/x.obj" ] && [ ! -e "$TMP/x.ply" ]; then ok
    else bad "unwrap $args: exit $rc, stderr $(cat "$TMP/err.txt")"; fi
done

echo "cli_keep_file: $pass passed, $fail failed"
[ $fail -eq 0 ]
