#!/usr/bin/env bash
# Texel density and tiles (--texels-per-unit): spot unwrapped (LSCM, quick)
# at a density whose charts cover 1.02 tiles of 1024 px, so they cannot fit
# one. Checked on the written OBJ by an independent numpy raster: several
# UDIM tiles, every face inside one tile, the density T on every chart, no
# two charts on one sample, charts at least --padding pixels apart and from
# the tile border at the tile resolution; neuv eval's per-tile efficiency
# and the report's tiles match the areas measured here. neuv pack does the
# same on an existing map. Refusals exit 2 with one line.
# usage: cli_tiles.sh /path/to/neuv
set -u
NEUV=${1:?usage: cli_tiles.sh /path/to/neuv}
HERE=$(cd "$(dirname "$0")" && pwd)
SHARED=${NEUV_SHARED:-$HERE/../../shared}
IN=$SHARED/meshes/spot.obj
TMP=${NEUV_TEST_TMP:-/tmp}/cli_tiles.$$
if [ ! -f "$IN" ]; then echo "SKIP: no $IN"; exit 77; fi
PY=
for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null && "$p" -c 'import numpy' 2>/dev/null; then PY=$p; break; fi
done
if [ -z "$PY" ]; then echo "SKIP: no python3 with numpy (scripts/setup.sh installs python3-numpy)"; exit 77; fi
mkdir -p "$TMP"
trap 'rm -rf "$TMP"' EXIT

passed=0 failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }
expect() { if eval "$2"; then ok; else bad "$1"; fi; }

# The checker: OBJ (v, vt, f v/vt) -> facts about its tiles, as key=value lines.
cat > "$TMP/check.py" <<'EOF'
import math, sys
import numpy as np

path, R, pad, T = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
V, VT, F = [], [], []
for line in open(path):
    t = line.split()
    if not t: continue
    if t[0] == 'v': V.append([float(x) for x in t[1:4]])
    elif t[0] == 'vt': VT.append([float(x) for x in t[1:3]])
    elif t[0] == 'f':
        c = [w.split('/') for w in t[1:]]
        assert len(c) == 3
        F.append([[int(a[0]) - 1, int(a[1]) - 1] for a in c])
V, VT, F = np.array(V), np.array(VT), np.array(F)
fv, ft = F[:, :, 0], F[:, :, 1]
P, Q = V[fv], VT[ft]                       # #F x 3 x 3, #F x 3 x 2
a3 = 0.5 * np.linalg.norm(np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]), axis=1)
e1, e2 = Q[:, 1] - Q[:, 0], Q[:, 2] - Q[:, 0]
auv = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
# Tile of each face: the unit square of its centroid; every corner inside it.
cell = np.floor(Q.mean(axis=1)).astype(int)
inside = np.all((Q >= cell[:, None, :] - 1e-9) & (Q <= cell[:, None, :] + 1 + 1e-9), axis=(1, 2))
tile = cell[:, 0] + 10 * cell[:, 1]
print('faces_outside_their_tile=%d' % np.count_nonzero(~inside))
print('tiles=%s' % ','.join(str(1001 + t) for t in sorted(set(tile.tolist()))))
m = a3 > 1e-12 * a3.mean()
# Border: the extreme points of a chart are its corners.
off = Q - cell[:, None, :]
print('border_min_px=%.6f' % (min(off.min(), (1 - off).min()) * R))
# Charts: UV-connected components (faces sharing a vt).
parent = list(range(len(VT)))
def find(x):
    while parent[x] != x:
        parent[x] = parent[parent[x]]; x = parent[x]
    return x
for f in ft:
    for k in (1, 2):
        a, b = find(f[0]), find(f[k])
        if a != b: parent[a] = b
chart = np.array([find(f[0]) for f in ft])
_, chart = np.unique(chart, return_inverse=True)
# Density per chart (the maps are not isometric face by face): UV area x R^2
# against T^2 x 3D area.
cu, c3 = np.bincount(chart, weights=auv), np.bincount(chart, weights=a3)
print('density_worst_rel=%.3g' % np.max(np.abs(np.sqrt(cu / c3) * R / T - 1)))
# Each tile rasterized at 4x its resolution (pixel centres inside a face,
# either orientation): no sample claimed by two charts, and samples of two
# charts at least 4 x pad sub-pixels apart (centres lie inside the charts,
# so this bounds the charts' own distance from above).
S = 4 * R
overlaps = close = 0
for t in sorted(set(tile.tolist())):
    img = np.full((S, S), -1, dtype=np.int32)
    for f in np.nonzero(tile == t)[0]:
        p = (Q[f] - cell[f]) * S
        x0, x1 = max(int(math.floor(p[:, 0].min())), 0), min(int(math.ceil(p[:, 0].max())), S - 1)
        y0, y1 = max(int(math.floor(p[:, 1].min())), 0), min(int(math.ceil(p[:, 1].max())), S - 1)
        if x1 < x0 or y1 < y0: continue
        X, Y = np.meshgrid(np.arange(x0, x1 + 1) + 0.5, np.arange(y0, y1 + 1) + 0.5)
        d = [(p[(k + 1) % 3, 0] - p[k, 0]) * (Y - p[k, 1]) - (p[(k + 1) % 3, 1] - p[k, 1]) * (X - p[k, 0]) for k in range(3)]
        inn = ((d[0] >= 0) & (d[1] >= 0) & (d[2] >= 0)) | ((d[0] <= 0) & (d[1] <= 0) & (d[2] <= 0))
        sub = img[y0:y1 + 1, x0:x1 + 1]
        overlaps += np.count_nonzero(inn & (sub >= 0) & (sub != chart[f]))
        sub[inn] = chart[f]
    occ = img >= 0
    edge = np.zeros_like(occ)
    edge[1:-1, 1:-1] = occ[1:-1, 1:-1] & ((img[1:-1, 1:-1] != img[:-2, 1:-1]) | (img[1:-1, 1:-1] != img[2:, 1:-1]) |
                                          (img[1:-1, 1:-1] != img[1:-1, :-2]) | (img[1:-1, 1:-1] != img[1:-1, 2:]))
    edge[0, :] |= occ[0, :]; edge[-1, :] |= occ[-1, :]; edge[:, 0] |= occ[:, 0]; edge[:, -1] |= occ[:, -1]
    ys, xs = np.nonzero(edge)
    c = img[ys, xs]
    r = 4 * pad
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            if dx * dx + dy * dy >= r * r or (dy, dx) <= (0, 0): continue
            yy, xx = ys + dy, xs + dx
            ok = (yy >= 0) & (yy < S) & (xx >= 0) & (xx < S)
            o = np.full(len(ys), -1)
            o[ok] = img[yy[ok], xx[ok]]
            close += np.count_nonzero((o >= 0) & (o != c))
    print('efficiency_%d=%.9f' % (1001 + t, auv[tile == t][m[tile == t]].sum()))
print('overlapped_samples=%d' % overlaps)
print('close_samples=%d' % close)
print('area3=%.12g' % a3.sum())
EOF

val() { sed -n "s/^$1=//p" "$2"; }

# The density at which spot's charts cover 1.02 tiles of 1024 px: at least two tiles.
"$PY" - "$IN" > "$TMP/area.txt" <<'EOF'
import sys, numpy as np
V, F = [], []
for line in open(sys.argv[1]):
    t = line.split()
    if t and t[0] == 'v': V.append([float(x) for x in t[1:4]])
    elif t and t[0] == 'f': F.append([int(w.split('/')[0]) - 1 for w in t[1:4]])
V, F = np.array(V), np.array(F)
A = 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1).sum()
print('%.6f' % (1024 * (1.02 / A) ** 0.5))
EOF
T=$(cat "$TMP/area.txt")
echo "T = $T px per unit"

"$NEUV" unwrap "$IN" --method lscm --texels-per-unit "$T" -o "$TMP/tiles.obj" --report "$TMP/tiles.json" \
    --preview "$TMP/tiles" > "$TMP/out.txt" 2> "$TMP/err.txt"
rc=$?
cat "$TMP/out.txt"
expect "unwrap --texels-per-unit exits 0 (got $rc: $(cat "$TMP/err.txt"))" "[ $rc -eq 0 ]"
expect "the summary gives the tiles" "grep -q 'over 2 tiles' '$TMP/out.txt' && grep -q '2 UDIM tiles: 1001 efficiency' '$TMP/out.txt'"
expect "preview written" "[ -s '$TMP/tiles-uv.png' ]"
"$PY" "$TMP/check.py" "$TMP/tiles.obj" 1024 2 "$T" > "$TMP/facts.txt"
cat "$TMP/facts.txt"
expect "two UDIM tiles, 1001 and 1002" "[ \"$(val tiles "$TMP/facts.txt")\" = 1001,1002 ]"
expect "every face inside one tile" "[ \"$(val faces_outside_their_tile "$TMP/facts.txt")\" = 0 ]"
expect "density T on every chart (1e-6)" "awk -v d='$(val density_worst_rel "$TMP/facts.txt")' 'BEGIN { exit !(d <= 1e-6) }'"
expect "2 px from every tile border" "awk -v d='$(val border_min_px "$TMP/facts.txt")' 'BEGIN { exit !(d >= 2 - 1e-6) }'"
expect "no sample in two charts" "[ \"$(val overlapped_samples "$TMP/facts.txt")\" = 0 ]"
expect "charts 2 px apart at 1024 px (4x raster)" "[ \"$(val close_samples "$TMP/facts.txt")\" = 0 ]"
e1=$(val efficiency_1001 "$TMP/facts.txt"); e2=$(val efficiency_1002 "$TMP/facts.txt")
expect "the tiles hold 1.02 tiles of chart area" "awk -v a='$e1' -v b='$e2' 'BEGIN { exit !(a + b > 1.0199 && a + b < 1.0201) }'"

# The report's tiles and neuv eval's per-tile efficiency match the areas measured here.
"$PY" - "$TMP/tiles.json" "$e1" "$e2" > "$TMP/report.txt" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
t = d['tiles']
ok = [x['udim'] for x in t] == [1001, 1002] and abs(t[0]['efficiency'] - float(sys.argv[2])) < 1e-6 \
     and abs(t[1]['efficiency'] - float(sys.argv[3])) < 1e-6 and sum(x['faces'] for x in t) == d['faces'] \
     and d['metrics']['overlap_fraction'] == 0 and d['pack']['texels_per_unit'] > 0 \
     and abs(d['pack']['efficiency'] - (t[0]['efficiency'] + t[1]['efficiency']) / 2) < 1e-6
print('ok' if ok else 'mismatch: %s' % t)
EOF
expect "report tiles match ($(cat "$TMP/report.txt"))" "grep -qx ok '$TMP/report.txt'"
"$NEUV" eval "$TMP/tiles.obj" > "$TMP/eval.txt" 2>&1
cat "$TMP/eval.txt" | tail -4
expect "eval prints two tiles" "grep -Eq '^  tiles +2 ' '$TMP/eval.txt'"
p1=$(awk '$1 == "1001" {print $2}' "$TMP/eval.txt"); p2=$(awk '$1 == "1002" {print $2}' "$TMP/eval.txt")
expect "eval's tile 1001 efficiency ($p1 vs $e1)" "awk -v a='$p1' -v b='$e1' 'BEGIN { exit !(a - b < 1e-5 && b - a < 1e-5) }'"
expect "eval's tile 1002 efficiency ($p2 vs $e2)" "awk -v a='$p2' -v b='$e2' 'BEGIN { exit !(a - b < 1e-5 && b - a < 1e-5) }'"
"$NEUV" eval "$TMP/tiles.obj" --json > "$TMP/eval.json"
expect "eval --json has both tiles" "'$PY' -c \"import json; t = json.load(open('$TMP/eval.json'))['tiles']; exit(not ([x['udim'] for x in t] == [1001, 1002]))\""

# neuv pack at 512 px tiles with 4 px padding and half the density: the same 1.02 tiles of chart area.
T2=$(awk -v t="$T" 'BEGIN { printf "%.6f", t / 2 }')
"$NEUV" pack "$TMP/tiles.obj" -o "$TMP/packed.obj" --resolution 512 --padding 4 --texels-per-unit "$T2" > "$TMP/pack.txt" 2>&1
rc=$?
head -1 "$TMP/pack.txt"
expect "pack --texels-per-unit exits 0" "[ $rc -eq 0 ]"
"$PY" "$TMP/check.py" "$TMP/packed.obj" 512 4 "$T2" > "$TMP/facts2.txt"
n=$(val tiles "$TMP/facts2.txt" | tr ',' '\n' | wc -l)
expect "pack: at least 2 tiles of 512 px (got $n)" "[ $n -ge 2 ]"
expect "pack: density, border, overlap, padding" "[ \"$(val faces_outside_their_tile "$TMP/facts2.txt")\" = 0 ] && \
    awk -v d='$(val density_worst_rel "$TMP/facts2.txt")' -v b='$(val border_min_px "$TMP/facts2.txt")' 'BEGIN { exit !(d <= 1e-6 && b >= 4 - 1e-6) }' && \
    [ \"$(val overlapped_samples "$TMP/facts2.txt")\" = 0 ] && [ \"$(val close_samples "$TMP/facts2.txt")\" = 0 ]"

# A density the charts fit one tile at: one tile, 1001.
T1=$(awk -v t="$T" 'BEGIN { print t * 0.7 }')
"$NEUV" unwrap "$IN" --method lscm --texels-per-unit "$T1" -o "$TMP/one.obj" --quiet
"$PY" "$TMP/check.py" "$TMP/one.obj" 1024 2 "$T1" > "$TMP/facts3.txt"
expect "T x 0.7: one tile" "[ \"$(val tiles "$TMP/facts3.txt")\" = 1001 ] && [ \"$(val close_samples "$TMP/facts3.txt")\" = 0 ]"

# Over --train-faces: the copy trains in one square, the full mesh is packed into tiles.
"$NEUV" unwrap "$IN" --method lscm --train-faces 2000 --texels-per-unit "$T" -o "$TMP/copy.obj" --quiet 2> /dev/null
"$PY" "$TMP/check.py" "$TMP/copy.obj" 1024 2 "$T" > "$TMP/facts4.txt"
expect "--train-faces: two tiles at T, padding kept" "[ \"$(val tiles "$TMP/facts4.txt")\" = 1001,1002 ] && \
    awk -v d='$(val density_worst_rel "$TMP/facts4.txt")' -v b='$(val border_min_px "$TMP/facts4.txt")' 'BEGIN { exit !(d <= 1e-6 && b >= 2 - 1e-6) }' && \
    [ \"$(val overlapped_samples "$TMP/facts4.txt")\" = 0 ] && [ \"$(val close_samples "$TMP/facts4.txt")\" = 0 ]"

# Refusals: exit 2, one line.
refuse() {
    local what=$1; shift
    "$NEUV" "$@" > /dev/null 2> "$TMP/refuse.txt"
    local rc=$?
    expect "$what exits 2 with one line (rc $rc: $(head -c 200 "$TMP/refuse.txt"))" \
        "[ $rc -eq 2 ] && [ \$(wc -l < '$TMP/refuse.txt') -eq 1 ] && grep -q 'neuv: error' '$TMP/refuse.txt'"
}
refuse "a chart larger than a tile" unwrap "$IN" --method lscm --texels-per-unit 100000 -o "$TMP/x.obj"
grep -q 'too large for one 1024 px tile' "$TMP/refuse.txt" && ok || bad "the message names the tile"
refuse "--texels-per-unit 0" unwrap "$IN" --texels-per-unit 0 -o "$TMP/x.obj"
refuse "--texels-per-unit -3" pack "$TMP/tiles.obj" -o "$TMP/x.obj" --texels-per-unit -3
refuse "--texels-per-unit with --keep-scale" pack "$TMP/tiles.obj" -o "$TMP/x.obj" --texels-per-unit 100 --keep-scale
refuse "--texels-per-unit with --save-model" unwrap "$IN" --texels-per-unit 100 --save-model "$TMP/m.neuv" -o "$TMP/x.obj"
refuse "--texels-per-unit with --model" unwrap "$IN" --texels-per-unit 100 --model "$TMP/m.neuv" -o "$TMP/x.obj"
grep -q -- '--texels-per-unit cannot be used with --model' "$TMP/refuse.txt" && ok || bad "the --model message names the flag"

echo "cli_tiles: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
