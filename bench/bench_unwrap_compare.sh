#!/usr/bin/env bash
# `neuv unwrap` (default options) of one build against another (a reference,
# e.g. main before a change) on shared meshes: the report's parameterization
# and total seconds, the two builds alternating run by run so that both see
# the same machine load, medians of RUNS; the atlas each build gives (qce_mean,
# the networks' own qce_mean, charts) to show that quality did not move, and
# whether the two wrote the same bytes (every run).
#
#   git worktree add /tmp/ref REV && make -C /tmp/ref build   # the reference build
#   bash bench/bench_unwrap_compare.sh /tmp/ref/build/neuv build/neuv [SHARED] [RUNS] [MESH...]
set -euo pipefail
REF=${1:?reference neuv}; NEW=${2:?neuv}; SHARED=${3:-../shared}; RUNS=${4:-3}
shift $(( $# < 4 ? $# : 4 ))
meshes=("$@"); [ ${#meshes[@]} -gt 0 ] || meshes=(spot.obj fandisk.obj homer.obj)
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
[ -d "$SHARED/meshes" ] || { echo "bench_unwrap_compare: no $SHARED/meshes" >&2; exit 77; }
echo "| mesh | faces | param s ref | param s this | ratio | total s ref | total s this | ratio | qce_mean ref / this | networks' qce ref / this | charts ref / this | same bytes |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---|---|---|---|"
for m in "${meshes[@]}"; do
  for ((i = 0; i < RUNS; i++)); do
    "$REF" unwrap "$SHARED/meshes/$m" -o "$TMP/ref.obj" --report "$TMP/ref$i.json" --quiet
    "$NEW" unwrap "$SHARED/meshes/$m" -o "$TMP/new.obj" --report "$TMP/new$i.json" --quiet
    cmp -s "$TMP/ref.obj" "$TMP/new.obj" && same=yes || same=no
    [ $i -eq 0 ] || [ "$same" = "$prev" ] || same=mixed
    prev=$same
  done
  python3 - "$m" "$TMP" "$RUNS" "$same" <<'PY'
import json, statistics, sys
name, tmp, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
load = lambda k: [json.load(open(f"{tmp}/{k}{i}.json")) for i in range(runs)]
a, b = load("ref"), load("new")
med = lambda rs, s: statistics.median(r["seconds"][s] for r in rs)
pa, pb, ta, tb = med(a, "param"), med(b, "param"), med(a, "total"), med(b, "total")
q = lambda r: r["metrics"]["qce_mean"]
nq = lambda r: r["provenance"]["network_qce_mean"] or float("nan")
print(f"| {name} | {a[0]['faces']} | {pa:.2f} | {pb:.2f} | {pb / pa:.2f} | {ta:.2f} | {tb:.2f} | {tb / ta:.2f} "
      f"| {q(a[0]):.4f} / {q(b[0]):.4f} | {nq(a[0]):.4f} / {nq(b[0]):.4f} "
      f"| {a[0]['metrics']['charts']} / {b[0]['metrics']['charts']} | {sys.argv[4]} |")
PY
done
