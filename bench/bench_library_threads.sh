#!/usr/bin/env bash
# What a program that embeds libneuv gets on T threads under libgomp's
# default wait policy (OMP_WAIT_POLICY unset: the library cannot change it
# once libgomp is loaded) against PASSIVE (what the CLI sets for itself by
# re-executing), alternating so that every policy sees the same machine
# load; medians of RUNS. POLICIES="default PASSIVE ACTIVE" adds spinning
# (minutes a run on 2 cores). Uses bench_library_threads (the public API
# only, no re-execution).
#
#   cmake --build build --target bench_library_threads
#   bash bench/bench_library_threads.sh MESH [threads] [runs]
set -euo pipefail
BIN=${BIN:-build/bench/bench_library_threads}
MESH=${1:?mesh}; T=${2:-2}; RUNS=${3:-3}
declare -A all
for ((i = 0; i < RUNS; i++)); do
  for p in ${POLICIES:-default PASSIVE}; do
    if [ $p = default ]; then line=$(env -u OMP_WAIT_POLICY "$BIN" "$MESH" "$T")
    else line=$(OMP_WAIT_POLICY=$p "$BIN" "$MESH" "$T"); fi
    echo "run $i $p: total operators patches param repair pack = $line (load $(cut -d' ' -f1 /proc/loadavg))"
    all[$p]+="$line"$'\n'
  done
done
for p in ${POLICIES:-default PASSIVE}; do
  printf '%s' "${all[$p]}" | python3 -c '
import sys, statistics
rows = [list(map(float, l.split())) for l in sys.stdin if l.strip()]
cols = ["total", "operators", "patches", "param", "repair", "pack"]
print(sys.argv[1].ljust(8), " ".join("%s %.2f" % (c, statistics.median(r[i] for r in rows)) for i, c in enumerate(cols)))
' "$p"
done
