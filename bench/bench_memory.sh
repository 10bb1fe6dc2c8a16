#!/usr/bin/env bash
# Issue 20 bench: peak memory against face count in the three paths that
# train on the whole mesh: `neuv unwrap --train-faces 0`, the library call
# (neuv_atlas_generate with its default train_faces 0, through
# bench/bench_library_threads) and `neuv train` (a category model of three
# shapes of that size). Meshes are made here: procedural blobs (neuv shape
# blob, members 1, 3 and 5) subdivided with `neuv remesh --subdivide N`, so
# each row has 4x the faces of the one before (5120 · 4^N faces).
#
#   bench/bench_memory.sh BUILD_DIR [OUT_DIR] [LEVELS] [ITERS]
#
# LEVELS: subdivision levels, default "0 1 2" (5k, 20k, 82k faces); 3 and 4
# give 328k and 1.31M. ITERS: training steps of PatchNet and of the
# networks (default 5): memory does not grow with the step count (every
# buffer is sized by the mesh before the first step), and full training of
# the larger rows takes hours on a 2-core machine. One thread, no operator
# cache. Peak memory is GNU time's maximum resident set size.
# Prints a table, then per path the ratio of KB per face between the largest
# and the smallest row (1.0: exactly linear).
set -eu
B="$1"; OUT="${2:-/tmp/bench_memory}"; LEVELS="${3:-0 1 2}"; ITERS="${4:-5}"
NEUV="$B/neuv"; LIB="$B/bench/bench_library_threads"
[ -x "$LIB" ] || cmake --build "$B" --target bench_library_threads >/dev/null
mkdir -p "$OUT"
for m in 1 3 5; do "$NEUV" shape blob --member $m -o "$OUT/blob$m-base.obj" >/dev/null; done
# Member 1 and 3 have 1280 faces, member 5 has 5120: one subdivision more
# for the first two, so that all three of a level have 5120 * 4^level faces.
peak() { # peak KB and seconds of a command, from GNU time's last line
  /usr/bin/time -f '%M %e' -o "$OUT/time.txt" "$@" >"$OUT/cmd.log" 2>&1 || { echo "failed: $*" >&2; tail -3 "$OUT/cmd.log" >&2; return 1; }
  cat "$OUT/time.txt"
}
echo "| faces | path | peak MB | KB per face | seconds |"
echo "|---:|---|---:|---:|---:|"
declare -A first last
for L in $LEVELS; do
  for m in 1 3 5; do
    n=$L; [ $m = 5 ] || n=$((L + 1))
    if [ "$n" -eq 0 ]; then cp "$OUT/blob$m-base.obj" "$OUT/blob$m-$L.obj"
    else "$NEUV" remesh "$OUT/blob$m-base.obj" --subdivide "$n" -o "$OUT/blob$m-$L.obj" >/dev/null; fi
  done
  mesh="$OUT/blob5-$L.obj"
  faces=$(grep -c '^f ' "$mesh")
  for path in cli library train; do
    case $path in
      cli) r=$(peak "$NEUV" unwrap "$mesh" -o "$OUT/out-$L.obj" --train-faces 0 --iters "$ITERS" --threads 1 --no-cache --quiet) ;;
      library) r=$(peak "$LIB" "$mesh" 1 "$ITERS") ;;
      train) r=$(peak "$NEUV" train -o "$OUT/cat-$L.neuv" "$OUT/blob1-$L.obj" "$OUT/blob3-$L.obj" "$OUT/blob5-$L.obj" \
                   --iters "$ITERS" --patch-iters "$ITERS" --threads 1 --no-cache --quiet) ;;
    esac
    kb=${r% *}; secs=${r#* }
    per=$(awk -v k="$kb" -v f="$faces" 'BEGIN { printf "%.2f", k / f }')
    [ $path = train ] && per=$(awk -v k="$kb" -v f="$faces" 'BEGIN { printf "%.2f", k / (3 * f) }')
    printf '| %d | %s | %.0f | %s | %s |\n' "$faces" "$path" "$(awk -v k="$kb" 'BEGIN { print k / 1024 }')" "$per" "$secs"
    [ -n "${first[$path]:-}" ] || first[$path]=$per
    last[$path]=$per
  done
done
echo
for path in cli library train; do
  awk -v a="${first[$path]}" -v b="${last[$path]}" -v p="$path" \
    'BEGIN { printf "%s: KB per face, largest row / smallest row = %.2f\n", p, b / a }'
done
echo "(train: KB per face of the three shapes together)"
