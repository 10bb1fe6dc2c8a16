#!/usr/bin/env bash
# Issue 8 bench: the default of --train-faces. Every mesh of ../shared/meshes
# above 20k faces is unwrapped with the networks trained on simplified copies
# of 10k, 20k and 40k faces (the model then applied to the full mesh) and on
# the full mesh (--train-faces 0): end-to-end seconds against quality.
# Usage: bench/bench_train_faces.sh BUILD_DIR [OUT_DIR] [budgets...]
set -eu
B="$1"; OUT="${2:-/tmp/bench_train_faces}"; NEUV="$B/neuv"
shift; [ $# -gt 0 ] && shift
BUDGETS=("$@"); [ ${#BUDGETS[@]} -gt 0 ] || BUDGETS=(10000 20000 40000 0)
SHARED="${NEUV_SHARED:-$(cd "$(dirname "$0")/../.." && pwd)/shared}"
mkdir -p "$OUT"
echo "| mesh | faces | --train-faces | seconds | charts | qce_mean | packing | flipped | overlap |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|"
for f in "$SHARED"/meshes/*; do
  n=$(grep -c '^f ' "$f" 2>/dev/null || true)
  [ "${n:-0}" -gt 20000 ] || continue
  name=$(basename "${f%.*}")
  for tf in "${BUDGETS[@]}"; do
    "$NEUV" unwrap "$f" --train-faces "$tf" -o "$OUT/$name-$tf.obj" --report "$OUT/$name-$tf.json" --quiet
    python3 - "$OUT/$name-$tf.json" "$name" "$tf" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); m = r["metrics"]
print(f"| {sys.argv[2]} | {r['faces']} | {sys.argv[3]} | {r['seconds']['total']:.1f} | {r['charts']} | {m['qce_mean']:.4f} | "
      f"{m['packing_efficiency']:.3f} | {m['flipped']} | {m['overlap_fraction']:.2g} |")
PY
  done
done
