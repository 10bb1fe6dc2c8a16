#!/usr/bin/env bash
# Texel density and tiles (bench/RESULTS.md, "Texel density and tiles"): one
# mesh unwrapped three times with the same charts and maps (same seed):
# packed into one square (the scale search), then at the density that
# square reached (T0: one tile), then at 1.2 T0 (more than one tile's worth
# of chart area). Prints tiles, per-tile efficiency and the packing stage's
# seconds from each report.
# usage: bench/bench_tiles.sh [build/neuv] [../shared/meshes/spot.obj] [extra unwrap flags...]
set -eu
NEUV=${1:-build/neuv}
MESH=${2:-../shared/meshes/spot.obj}
shift 2 2>/dev/null || shift $#
PY=/usr/bin/python3
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
run() { # name, flags...
    local name=$1; shift
    "$NEUV" unwrap "$MESH" -o "$TMP/$name.obj" --report "$TMP/$name.json" --quiet "$@"
}
run square "$@"
T0=$("$PY" - "$MESH" "$TMP/square.json" <<'PYEOF'
import json, sys
import numpy as np
V, F = [], []
for line in open(sys.argv[1]):
    t = line.split()
    if t and t[0] == 'v': V.append([float(x) for x in t[1:4]])
    elif t and t[0] == 'f': F.append([int(w.split('/')[0]) - 1 for w in t[1:4]])
V, F = np.array(V), np.array(F)
A = 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1).sum()
r = json.load(open(sys.argv[2]))
print('%.4f' % (r['pack']['resolution'] * (r['metrics']['packing_efficiency'] / A) ** 0.5))
PYEOF
)
T1=$(awk -v t="$T0" 'BEGIN { printf "%.4f", 1.2 * t }')
run t0 --texels-per-unit "$T0" "$@"
run t1 --texels-per-unit "$T1" "$@"
echo "| run | texels per unit | tiles | efficiency per tile | mean | qce_mean | pack s | total s |"
echo "|---|---:|---:|---|---:|---:|---:|---:|"
for name in square t0 t1; do
    "$PY" - "$TMP/$name.json" "$name" "$T0" "$T1" <<'PYEOF'
import json, sys
r = json.load(open(sys.argv[1]))
label = {'square': 'one square (scale search)', 't0': 'T0 = the square\'s density', 't1': '1.2 T0'}[sys.argv[2]]
T = {'square': sys.argv[3], 't0': sys.argv[3], 't1': sys.argv[4]}[sys.argv[2]]
t = r['tiles']
print('| %s | %s | %d | %s | %.3f | %.4f | %.2f | %.1f |' % (
    label, T if sys.argv[2] != 'square' else '(%s)' % T, len(t),
    ', '.join('%d: %.3f' % (x['udim'], x['efficiency']) for x in t), r['pack']['efficiency'],
    r['metrics']['qce_mean'], r['seconds']['pack'], r['seconds']['total']))
PYEOF
done
