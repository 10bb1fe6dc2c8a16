#!/usr/bin/env bash
# Issue 8 bench: spot.obj unwrapped with --save-model --refine 0 (the
# networks' map unrefined, as when the figures were measured), the model applied to
# the jittered subdivision and to 50% / 20% simplifications of the unwrapped
# mesh (seams kept, see tests/cli_model.sh), compared with `neuv compare`;
# beside it two independent unwraps (seeds 1 and 2) as the per-mesh baseline.
# Usage: bench/bench_transfer.sh BUILD_DIR [OUT_DIR]   (timings with --threads 1)
set -eu
B="$1"; OUT="${2:-/tmp/bench_transfer}"; NEUV="$B/neuv"
SPOT="${NEUV_SHARED:-/work/shared}/meshes/spot.obj"
mkdir -p "$OUT"
"$NEUV" unwrap "$SPOT" -o "$OUT/spot-uv.obj" --save-model "$OUT/spot.neuv" --refine 0 --threads 1 --report "$OUT/src.json" --quiet
"$NEUV" unwrap "$SPOT" -o "$OUT/spot-uv2.obj" --seed 2 --threads 1 --quiet
"$NEUV" remesh "$OUT/spot-uv.obj" -o "$OUT/sub.obj" --subdivide 1 --jitter --quiet
"$NEUV" remesh "$OUT/spot-uv.obj" -o "$OUT/s50.obj" --simplify 0.5 --quiet
"$NEUV" remesh "$OUT/spot-uv.obj" -o "$OUT/s20.obj" --simplify 0.2 --quiet
printf "%-22s %7s %9s %9s %8s %7s %8s %7s\n" case faces uv_mean uv_p95 agree flips overlap infer_s
for x in sub s50 s20; do
  "$NEUV" unwrap "$OUT/$x.obj" --model "$OUT/spot.neuv" -o "$OUT/$x-uv.obj" --report "$OUT/$x.json" --threads 1 --quiet
  "$NEUV" compare "$OUT/spot-uv.obj" "$OUT/$x-uv.obj" --json > "$OUT/$x-cmp.json"
  python3 - "$OUT/$x.json" "$OUT/$x-cmp.json" "model->$x" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); c = json.load(open(sys.argv[2])); m = r["metrics"]
print("%-22s %7d %9.2e %9.2e %8.4f %7d %8.2g %7.2f" % (sys.argv[3], r["faces"], c["uv_distance"]["mean"],
      c["uv_distance"]["p95"], c["chart_agreement"], m["flipped"], m["overlap_fraction"], r["model"]["inference_seconds"]))
PY
done
"$NEUV" compare "$OUT/spot-uv.obj" "$OUT/spot-uv2.obj" --json > "$OUT/base-cmp.json"
python3 -c "
import json; c=json.load(open('$OUT/base-cmp.json'))
print('%-22s %7d %9.2e %9.2e %8.4f' % ('baseline seed1 vs 2', c['faces_b'], c['uv_distance']['mean'], c['uv_distance']['p95'], c['chart_agreement']))"
