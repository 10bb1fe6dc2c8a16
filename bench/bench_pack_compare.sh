#!/usr/bin/env bash
# `neuv pack` of one build against another (a reference, e.g. main before a
# change), on every UV map in ../shared/uv-samples and on neuv's own LSCM
# unwrap of spot: wall seconds of the whole process, the two builds
# alternating run by run so that both see the same machine load, medians of
# RUNS; "same bytes" says whether the two wrote identical files.
#
#   git worktree add /tmp/ref REV && make -C /tmp/ref build   # the reference build
#   bash bench/bench_pack_compare.sh /tmp/ref/build/neuv build/neuv [SHARED] [RUNS]
set -euo pipefail
REF=${1:?reference neuv}; NEW=${2:?neuv}; SHARED=${3:-../shared}; RUNS=${4:-3}
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
[ -d "$SHARED/uv-samples" ] || { echo "bench_pack_compare: no $SHARED/uv-samples" >&2; exit 77; }
inputs=("$SHARED"/uv-samples/*.obj)
if [ -f "$SHARED/meshes/spot.obj" ]; then
  "$NEW" unwrap "$SHARED/meshes/spot.obj" --method lscm --threads 1 -o "$TMP/spot-neuv-lscm.obj" --quiet
  inputs+=("$TMP/spot-neuv-lscm.obj")
fi
secs() { local t0 t1; t0=$(date +%s%N); "$@"; t1=$(date +%s%N); echo $(( (t1 - t0) / 1000000 ))e-3; }
echo "| file | charts | efficiency | reference s | this build s | ratio | same bytes |"
echo "|---|---:|---:|---:|---:|---:|---|"
for f in "${inputs[@]}"; do
  a=(); b=()
  for ((i = 0; i < RUNS; i++)); do
    a+=("$(secs "$REF" pack "$f" -o "$TMP/ref.obj" --quiet)")
    b+=("$(secs "$NEW" pack "$f" -o "$TMP/new.obj" --quiet)")
  done
  same=no; cmp -s "$TMP/ref.obj" "$TMP/new.obj" && same=yes
  "$NEW" eval "$TMP/new.obj" --json > "$TMP/eval.json"
  python3 - "$(basename "$f")" "$TMP/eval.json" "$same" "${a[*]}" "${b[*]}" <<'PY'
import json, statistics, sys
name, ev, same, a, b = sys.argv[1:6]
m = json.load(open(ev))["metrics"]
ma, mb = statistics.median(map(float, a.split())), statistics.median(map(float, b.split()))
print(f"| {name} | {m['charts']} | {m['packing_efficiency']:.4f} | {ma:.2f} | {mb:.2f} | {mb / ma:.2f} | {same} |")
PY
done
