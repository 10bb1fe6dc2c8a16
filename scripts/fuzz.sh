#!/usr/bin/env bash
# Builds neuv's libFuzzer targets with clang (ASan + UBSan + coverage) and
# runs each for a while on a copy of its checked-in corpus.
#
#   bash scripts/fuzz.sh [-t SECONDS] [-j PARALLEL] [--merge] [TARGET...]
#
# TARGET: checkpoint obj off ply gltf model eval (all when none is named).
# -t: seconds per target (default 60); -j: targets run at once (default 1).
# --merge: afterwards, merge each run's corpus into the checked-in one
# (libFuzzer -merge=1: only inputs that add coverage are added).
# Crashes land in build-fuzz/crashes/TARGET-*; each run's log in
# build-fuzz/logs/TARGET.log. A final table gives, per target: seconds,
# executions, edges covered (cov), features (ft), corpus size, crashes.
# Exit 1 when a target crashed. Installs clang, compiler-rt and libomp from
# Debian when missing (root or sudo), as scripts/setup.sh does.
set -euo pipefail
cd "$(dirname "$0")/.."

SECONDS_PER=60 PAR=1 MERGE=0 TARGETS=()
while [ $# -gt 0 ]; do
  case "$1" in
    -t) SECONDS_PER="$2"; shift 2 ;;
    -j) PAR="$2"; shift 2 ;;
    --merge) MERGE=1; shift ;;
    -h|--help) sed -n 2,16p "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
    *) TARGETS+=("$1"); shift ;;
  esac
done
ALL=(checkpoint obj off ply gltf model eval)
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=("${ALL[@]}")
for t in "${TARGETS[@]}"; do
  case " ${ALL[*]} " in *" $t "*) ;; *) echo "fuzz.sh: unknown target '$t' (one of: ${ALL[*]})" >&2; exit 2 ;; esac
done

bash scripts/setup.sh
need=()
for p in clang libclang-rt-14-dev libomp-14-dev time; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO=sudo
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${need[@]}"
fi

B=build-fuzz
cmake -S . -B $B -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DNEUV_FUZZ=ON >/dev/null
cmake --build $B -j "$(nproc)" --target $(printf 'fuzz_%s ' "${TARGETS[@]}")
mkdir -p $B/logs $B/crashes $B/work

corpus_of() { if [ "$1" = checkpoint ]; then echo tests/fuzz/corpus; else echo "tests/fuzz/corpus_$1"; fi; }

run_one() {
  local t=$1 work=$B/work/$1 corpus
  corpus=$(corpus_of "$t")
  rm -rf "$work"; mkdir -p "$work" $B/run; cp -r "$corpus"/. "$work"/
  rm -f "$B/crashes/$t-"* "$B/logs/$t.log"
  # ASan's default leak check stays on: a leak is a finding like a crash.
  # A copy of the binary runs, so that a rebuild meanwhile does not pull it away.
  cp $B/fuzz/fuzz_$t $B/run/fuzz_$t
  # max_len: the largest checked-in input (a saved model is 256 KiB), at least 4 KiB.
  local maxlen
  maxlen=$(find "$corpus" -type f -printf '%s\n' | sort -n | tail -1)
  [ "${maxlen:-0}" -ge 4096 ] || maxlen=4096
  # ASan's default leak check stays on: a leak is a finding like a crash.
  # GNU time appends the CPU seconds the run really had (fuzzers sharing
  # cores get less than their wall time).
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  /usr/bin/time -a -o "$B/logs/$t.log" -f 'cpu_seconds: %U %S' \
  $B/run/fuzz_$t -max_total_time="$SECONDS_PER" -max_len="$maxlen" -timeout=25 -rss_limit_mb=4096 \
    -print_final_stats=1 -artifact_prefix="$B/crashes/$t-" "$work" >"$B/logs/$t.log" 2>&1 || true
}

i=0
for t in "${TARGETS[@]}"; do
  run_one "$t" &
  i=$((i + 1))
  if [ $((i % PAR)) -eq 0 ]; then wait; fi
done
wait

status=0
printf '| target | wall s | CPU s | executions | exec/s | cov | ft | corpus | crashes |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n'
for t in "${TARGETS[@]}"; do
  log=$B/logs/$t.log
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")
  corp=$(find "$B/work/$t" -type f | wc -l)
  crashes=$(find "$B/crashes" -name "$t-*" -type f | wc -l)
  cpu=$(awk '/^cpu_seconds:/ {printf "%.0f", $2 + $3}' "$log" | tail -1)
  [ "$crashes" -eq 0 ] || status=1
  printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$t" "$SECONDS_PER" "${cpu:-?}" "${execs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" "$corp" "$crashes"
done

if [ $MERGE -eq 1 ]; then
  for t in "${TARGETS[@]}"; do
    corpus=$(corpus_of "$t")
    before=$(find "$corpus" -type f | wc -l)
    $B/fuzz/fuzz_$t -merge=1 "$corpus" "$B/work/$t" >"$B/logs/$t.merge.log" 2>&1 || true
    echo "merge $t: $before -> $(find "$corpus" -type f | wc -l) files"
  done
fi
exit $status
