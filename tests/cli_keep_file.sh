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
#  - --uv-channel 1 keeps a PLY's and a GLB's UVs bit for bit as the first
#    set with the atlas as the second; it is refused for OBJ output (one UV
#    set) and for a file without UVs, with exit 2.
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

# 3. --uv-channel 1 keeps the first UV set bit for bit: a PLY written here
# (ASCII, float s t) and a GLB that neuv wrote (TEXCOORD_0), each
# unwrapped again with the atlas as the second set.
cat > "$TMP/uvsets.py" <<'PYEOF'
import json, struct, sys

def ply_corners(path):
    """Per face corner: {property: value} of its vertex (binary little endian or ASCII)."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    fmt = header[1].split()[1]
    elements, cur = [], None
    for line in header:
        w = line.split()
        if w[0] == "element":
            cur = [w[1], int(w[2]), []]
            elements.append(cur)
        elif w[0] == "property":
            cur[2].append(w[1:])
    codes = {"float": "f", "double": "d", "uchar": "B", "int": "i", "uint": "I", "char": "b", "short": "h",
             "ushort": "H", "float32": "f", "float64": "d", "uint8": "B", "int32": "i", "uint32": "I"}
    pos, out = end, {}
    text = data[end:].decode().split() if fmt == "ascii" else None
    ti = 0
    for name, count, props in elements:
        rows = []
        for _ in range(count):
            row = {}
            for p in props:
                if p[0] == "list":
                    if text is not None:
                        n = int(text[ti]); ti += 1
                        row[p[3]] = [int(x) for x in text[ti:ti + n]]; ti += n
                    else:
                        n = struct.unpack_from("<" + codes[p[1]], data, pos)[0]; pos += struct.calcsize(codes[p[1]])
                        c = codes[p[2]]
                        row[p[3]] = list(struct.unpack_from("<%d%s" % (n, c), data, pos)); pos += n * struct.calcsize(c)
                else:
                    c = codes[p[0]]
                    if text is not None:
                        v = float(text[ti]); ti += 1
                        row[p[1]] = struct.unpack("<f", struct.pack("<f", v))[0] if c == "f" else v
                    else:
                        row[p[1]] = struct.unpack_from("<" + c, data, pos)[0]; pos += struct.calcsize(c)
            rows.append(row)
        out[name] = rows
    return [[out["vertex"][v] for v in f["vertex_indices"]] for f in out["face"]]

def glb_corners(path):
    """Per triangle corner: (position, TEXCOORD_0, TEXCOORD_1 or None), over the primitives in order."""
    data = open(path, "rb").read()
    jlen = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + jlen])
    binary = data[20 + jlen + 8:]
    def read(acc_index):
        acc = doc["accessors"][acc_index]
        view = doc["bufferViews"][acc["bufferView"]]
        n = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}[acc["type"]]
        c = {5126: "f", 5125: "I", 5123: "H"}[acc["componentType"]]
        off = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        vals = struct.unpack_from("<%d%s" % (acc["count"] * n, c), binary, off)
        return [vals[i * n:(i + 1) * n] for i in range(acc["count"])]
    corners = []
    for prim in doc["meshes"][0]["primitives"]:
        a = prim["attributes"]
        p, t0 = read(a["POSITION"]), read(a["TEXCOORD_0"])
        t1 = read(a["TEXCOORD_1"]) if "TEXCOORD_1" in a else None
        for (i,) in read(prim["indices"]):
            corners.append((p[i], t0[i], t1[i] if t1 else None))
    return corners
PYEOF
"$PY" - "$TMP" <<'PYEOF'
import sys
tmp = sys.argv[1]
# A 6 x 3 grid of quads with its own UVs (a 0.1-step lattice squeezed into a corner).
n, m = 6, 3
lines = ["ply", "format ascii 1.0", "element vertex %d" % ((n + 1) * (m + 1)),
         "property float x", "property float y", "property float z", "property float s", "property float t",
         "element face %d" % (n * m), "property list uchar int vertex_indices", "end_header"]
for j in range(m + 1):
    for i in range(n + 1):
        lines.append("%g %g %g %.7g %.7g" % (i, j, 0.1 * ((i * j) % 3), 0.013 * i + 0.1, 0.021 * j + 0.2))
for j in range(m):
    for i in range(n):
        a = j * (n + 1) + i
        lines.append("4 %d %d %d %d" % (a, a + 1, a + n + 2, a + n + 1))
open(f"{tmp}/uv.ply", "w").write("\n".join(lines) + "\n")
PYEOF
if "$NEUV" unwrap "$TMP/uv.ply" -o "$TMP/uv2.ply" --uv-channel 1 --method lscm --quiet 2>"$TMP/uv2.err"; then
    out=$("$PY" - "$TMP" <<'PYEOF'
import sys
sys.path.insert(0, sys.argv[1])
import uvsets
tmp = sys.argv[1]
a, b = uvsets.ply_corners(f"{tmp}/uv.ply"), uvsets.ply_corners(f"{tmp}/uv2.ply")
problems = []
if [len(f) for f in a] != [len(f) for f in b]:
    problems.append("faces differ")
first = [(c["s"], c["t"]) for f in a for c in f]
kept = [(c.get("s"), c.get("t")) for f in b for c in f]
atlas = [(c.get("s1"), c.get("t1")) for f in b for c in f]
if first != kept:
    problems.append("the first UV pair changed")
if any(u is None or not (0 <= u <= 1 and 0 <= v <= 1) for u, v in atlas) or atlas == kept:
    problems.append("no atlas as the second pair")
print("; ".join(problems) if problems else "ok")
PYEOF
)
    [ "$out" = ok ] && ok || bad "uv.ply --uv-channel 1: $out"
else bad "unwrap uv.ply --uv-channel 1: $(cat "$TMP/uv2.err")"; fi
if "$NEUV" unwrap "$TMP/parts.obj" -o "$TMP/parts.glb" --method lscm --quiet 2>"$TMP/glb.err" &&
   "$NEUV" unwrap "$TMP/parts.glb" -o "$TMP/parts2.glb" --uv-channel 1 --method lscm --seed 3 --quiet 2>"$TMP/glb.err"; then
    out=$("$PY" - "$TMP" <<'PYEOF'
import sys
sys.path.insert(0, sys.argv[1])
import uvsets
tmp = sys.argv[1]
a, b = uvsets.glb_corners(f"{tmp}/parts.glb"), uvsets.glb_corners(f"{tmp}/parts2.glb")
problems = []
# The primitives (one per material) come in the same order, so corners match one to one.
if [c[0] for c in a] != [c[0] for c in b]:
    problems.append("positions per corner differ")
if [c[1] for c in a] != [c[1] for c in b]:
    problems.append("TEXCOORD_0 changed")
if any(c[2] is None for c in b) or any(not (0 <= x <= 1) for c in b for x in c[2]):
    problems.append("no atlas as TEXCOORD_1")
elif all(tuple(c[1]) == tuple(c[2]) for c in b):
    problems.append("TEXCOORD_1 equals TEXCOORD_0: the check could not tell a kept first set from the atlas")
print("; ".join(problems) if problems else "ok")
PYEOF
)
    [ "$out" = ok ] && ok || bad "parts.glb --uv-channel 1: $out"
else bad "glb round: $(cat "$TMP/glb.err")"; fi

# 4. --uv-channel 1 where it cannot be honoured: exit 2, one line.
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
