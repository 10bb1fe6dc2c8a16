#!/usr/bin/env bash
# `neuv pack` on one thread against T threads (OMP_NUM_THREADS), on every
# UV map in ../shared/uv-samples and on neuv's own LSCM unwrap of spot: the
# packer tries its placement heuristics side by side and runs the polish's
# next try beside the current one, and must give the same bytes as on one
# thread. One thread and T threads alternate run by run so that both see the
# same machine load; medians of RUNS wall seconds of the whole process.
#
#   bash bench/bench_pack_threads.sh [NEUV] [SHARED] [T] [RUNS]
set -euo pipefail
NEUV=${1:-build/neuv}; SHARED=${2:-../shared}; T=${3:-2}; RUNS=${4:-3}
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
[ -d "$SHARED/uv-samples" ] || { echo "bench_pack_threads: no $SHARED/uv-samples" >&2; exit 77; }
inputs=("$SHARED"/uv-samples/*.obj)
if [ -f "$SHARED/meshes/spot.obj" ]; then
  "$NEUV" unwrap "$SHARED/meshes/spot.obj" --method lscm --threads 1 -o "$TMP/spot-neuv-lscm.obj" --quiet
  inputs+=("$TMP/spot-neuv-lscm.obj")
fi
secs() { local t0 t1; t0=$(date +%s%N); "$@"; t1=$(date +%s%N); echo $(( (t1 - t0) / 1000000 ))e-3; }
echo "| file | charts | 1 thread s | $T threads s | ratio | same bytes |"
echo "|---|---:|---:|---:|---:|---|"
for f in "${inputs[@]}"; do
  a=(); b=()
  for ((i = 0; i < RUNS; i++)); do
    a+=("$(OMP_NUM_THREADS=1 secs "$NEUV" pack "$f" -o "$TMP/one.obj" --quiet)")
    b+=("$(OMP_NUM_THREADS=$T secs "$NEUV" pack "$f" -o "$TMP/many.obj" --quiet)")
  done
  same=no; cmp -s "$TMP/one.obj" "$TMP/many.obj" && same=yes
  charts=$("$NEUV" eval "$TMP/one.obj" --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["metrics"]["charts"])')
  python3 - "$(basename "$f")" "$charts" "$same" "${a[*]}" "${b[*]}" <<'EOF'
import statistics, sys
name, charts, same, a, b = sys.argv[1:6]
ma, mb = statistics.median(map(float, a.split())), statistics.median(map(float, b.split()))
print(f"| {name} | {charts} | {ma:.2f} | {mb:.2f} | {mb / ma:.2f} | {same} |")
EOF
  [ "$same" = yes ] || { echo "bench_pack_threads: $f packs differently on $T threads" >&2; exit 1; }
done
