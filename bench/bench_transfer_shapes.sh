#!/usr/bin/env bash
# A model applied to independent remeshes of generated shapes (not in ../shared):
# each shape is unwrapped with --save-model --refine 0, remeshed at half and twice
# its faces (`neuv remesh --faces`) and jittered within its surface, and the model
# applied to each. Prints per target: source faces, mean and p95 UV distance in the
# matched chart, chart agreement (plain closest point, then facing), flipped faces,
# overlap, target faces, charts, charts moved or shrunk, pieces kept as charts.
# Usage: bash bench/bench_transfer_shapes.sh BUILD_DIR [OUT_DIR]
set -euo pipefail
NEUV="$(cd "$1" && pwd)/neuv"
OUT="${2:-/tmp/bench_transfer_shapes}"
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
mkdir -p "$OUT"
cd "$OUT"
for s in "genus2" "blob --member 3" "bent-capsule --member 5"; do
  name=$(echo "$s" | tr -d ' -')
  "$NEUV" shape $s -o "$name.obj" > /dev/null
  "$NEUV" unwrap "$name.obj" -o "$name-src.obj" --save-model "$name.neuv" --refine 0 --threads 1 --quiet
  F=$(grep -c '^f ' "$name.obj")
  for k in 0.5 2; do
    t="$name-$k"
    "$NEUV" remesh "$name.obj" --faces "$("$PY" -c "print(int($k * $F))")" -o "$t.obj" --quiet
    "$NEUV" remesh "$t.obj" --jitter -o "${t}j.obj" --quiet
    for u in "$t" "${t}j"; do
      "$NEUV" unwrap "$u.obj" --model "$name.neuv" -o "$u-uv.obj" --report "$u.json" --threads 1 --quiet
      "$NEUV" compare "$name-src.obj" "$u-uv.obj" --json > "$u-cmp.json"
      "$PY" - "$u" "$F" "$u-cmp.json" "$u.json" <<'PYEOF'
import json, sys
d = json.load(open(sys.argv[3])); r = json.load(open(sys.argv[4])); m = r["model"]
print(sys.argv[1], sys.argv[2], "%.2e %.2e %.4f %.4f %d %g" % (
    d["uv_distance"]["mean"], d["uv_distance"]["p95"], d["chart_agreement"], d["chart_agreement_facing"],
    d["b_flipped"], d["b_overlap_fraction"]), r["faces"], r["charts"], m["moved_charts"], m["fragment_charts"])
PYEOF
    done
  done
done
