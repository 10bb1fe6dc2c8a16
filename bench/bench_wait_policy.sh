#!/usr/bin/env bash
# How libgomp's idle threads should wait (src/cli/main.c, choose_openmp_wait):
# `neuv unwrap MESH --threads 2 --iters 300` under PASSIVE, libgomp's default
# spin and a brief spin (GOMP_SPINCOUNT=10000), on the machine as it is
# ("idle") and beside two CPU-bound shell loops ("busy"). The policies
# alternate within each round; medians of RUNS rounds. The environment is set
# explicitly (libgomp's default spin is GOMP_SPINCOUNT=300000), so the CLI's
# own choice does not apply.
#
#   bench/bench_wait_policy.sh BUILD_DIR [MESH] [RUNS]
set -eu
B="$1"; MESH="${2:-${NEUV_SHARED:-$(dirname "$0")/../../shared}/meshes/spot.obj}"; RUNS="${3:-3}"
OUT=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$OUT"' EXIT
POLICIES=("passive OMP_WAIT_POLICY=PASSIVE" "default GOMP_SPINCOUNT=300000" "spin1e4 GOMP_SPINCOUNT=10000")
one() { # seconds of one run under the environment given
  env "$@" /usr/bin/time -f "%e" -o "$OUT/t" "$B/neuv" unwrap "$MESH" -o "$OUT/o.obj" --threads 2 --iters 300 --quiet
  cat "$OUT/t"
}
median() { sort -n | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }'; }
for load in idle busy; do
  pids=()
  if [ $load = busy ]; then
    for _ in 1 2; do sh -c 'while :; do :; done' & pids+=($!); done
    sleep 1
  fi
  for ((r = 0; r < RUNS; r++)); do
    for p in "${POLICIES[@]}"; do
      set -- $p
      one "${@:2}" >> "$OUT/$load-$1"
    done
  done
  [ ${#pids[@]} = 0 ] || kill "${pids[@]}"
  for p in "${POLICIES[@]}"; do
    set -- $p
    printf '%s %s: median %s s (runs: %s)\n' "$load" "$1" "$(median < "$OUT/$load-$1")" "$(paste -sd' ' "$OUT/$load-$1")"
  done
done
