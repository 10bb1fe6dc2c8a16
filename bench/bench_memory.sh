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
#
# MESH=FILE makes the rows from FILE instead (level N: FILE subdivided N
# times, 4^N its faces: the issue's armadillo rows); `train` then trains on
# four shapes of a quarter of the row's faces each (level N-1; for level 0 a
# CGAL remesh of FILE to a quarter of its faces), so that it counts the same
# faces as the other two paths. MAXMEM=MIB raises the up-front memory budget
# (--max-memory; the library's max_memory_mb), for rows over half of the
# machine's memory. PATHS="cli library train" (the default) picks the paths
# to run, for rows too long to run all three at once.
set -eu
B="$1"; OUT="${2:-/tmp/bench_memory}"; LEVELS="${3:-0 1 2}"; ITERS="${4:-5}"
MESH="${MESH:-}"; MAXMEM="${MAXMEM:-0}"; PATHS="${PATHS:-cli library train}"
NEUV="$B/neuv"; LIB="$B/bench/bench_library_threads"
[ -x "$LIB" ] || cmake --build "$B" --target bench_library_threads >/dev/null
mkdir -p "$OUT"
MEM=(); [ "$MAXMEM" = 0 ] || MEM=(--max-memory "$MAXMEM")
declare -A first last
peak() { # peak KB and seconds of a command, from GNU time's last line
  /usr/bin/time -f '%M %e' -o "$OUT/time.txt" "$@" >"$OUT/cmd.log" 2>&1 || { echo "failed: $*" >&2; tail -3 "$OUT/cmd.log" >&2; return 1; }
  cat "$OUT/time.txt"
}
row() { # one table row: faces, path, peak KB, seconds, faces counted
  printf '| %d | %s | %.0f | %s | %s |\n' "$1" "$2" "$(awk -v k="$3" 'BEGIN { print k / 1024 }')" \
    "$(awk -v k="$3" -v f="$5" 'BEGIN { printf "%.2f", k / f }')" "$4"
}
mesh_rows() {
  echo "| faces | path | peak MB | KB per face | seconds |"
  echo "|---:|---|---:|---:|---:|"
  local base="$OUT/mesh-0.obj" f0 first_kb="" L
  cp "$MESH" "$base"
  f0=$(grep -c '^f ' "$base")
  "$NEUV" remesh "$base" --faces $((f0 / 4)) -o "$OUT/mesh--1.obj" >/dev/null
  for L in $LEVELS; do
    [ "$L" = 0 ] || [ -f "$OUT/mesh-$L.obj" ] || "$NEUV" remesh "$base" --subdivide "$L" -o "$OUT/mesh-$L.obj" >/dev/null
    local prev=$((L - 1)) m="$OUT/mesh-$L.obj" faces tf r
    [ "$prev" -lt 1 ] || [ -f "$OUT/mesh-$prev.obj" ] || "$NEUV" remesh "$base" --subdivide "$prev" -o "$OUT/mesh-$prev.obj" >/dev/null
    faces=$(grep -c '^f ' "$m")
    tf=$((4 * $(grep -c '^f ' "$OUT/mesh-$prev.obj")))
    for path in $PATHS; do
      case $path in
        cli) r=$(peak "$NEUV" unwrap "$m" -o "$OUT/out-$L.obj" --train-faces 0 --iters "$ITERS" --threads 1 --no-cache --quiet "${MEM[@]}") ;;
        library) r=$(peak "$LIB" "$m" 1 "$ITERS" "$MAXMEM") ;;
        train) r=$(peak "$NEUV" train -o "$OUT/cat-$L.neuv" "$OUT/mesh-$prev.obj" "$OUT/mesh-$prev.obj" "$OUT/mesh-$prev.obj" \
                     "$OUT/mesh-$prev.obj" --iters "$ITERS" --patch-iters "$ITERS" --threads 1 --no-cache --quiet "${MEM[@]}") ;;
      esac
      local n=$faces; [ $path = train ] && n=$tf
      row "$n" "$path" "${r% *}" "${r#* }" "$n"
      local pf; pf=$(awk -v k="${r% *}" -v f="$n" 'BEGIN { print k / f }')
      [ -n "${first[$path]:-}" ] || first[$path]=$pf
      last[$path]=$pf
    done
  done
  summary "(train: four shapes of a quarter of the row's faces each)"
}
summary() { # per path: KB per face of the last row over the first's
  echo
  for path in $PATHS; do
    awk -v a="${first[$path]}" -v b="${last[$path]}" -v p="$path" \
      'BEGIN { printf "%s: KB per face, largest row / smallest row = %.2f\n", p, b / a }'
  done
  echo "$1"
}
if [ -n "$MESH" ]; then
  mesh_rows "$@"
  exit
fi
for m in 1 3 5; do "$NEUV" shape blob --member $m -o "$OUT/blob$m-base.obj" >/dev/null; done
# Member 1 and 3 have 1280 faces, member 5 has 5120: one subdivision more
# for the first two, so that all three of a level have 5120 * 4^level faces.
echo "| faces | path | peak MB | KB per face | seconds |"
echo "|---:|---|---:|---:|---:|"
for L in $LEVELS; do
  for m in 1 3 5; do
    n=$L; [ $m = 5 ] || n=$((L + 1))
    if [ "$n" -eq 0 ]; then cp "$OUT/blob$m-base.obj" "$OUT/blob$m-$L.obj"
    else "$NEUV" remesh "$OUT/blob$m-base.obj" --subdivide "$n" -o "$OUT/blob$m-$L.obj" >/dev/null; fi
  done
  mesh="$OUT/blob5-$L.obj"
  faces=$(grep -c '^f ' "$mesh")
  for path in $PATHS; do
    case $path in
      cli) r=$(peak "$NEUV" unwrap "$mesh" -o "$OUT/out-$L.obj" --train-faces 0 --iters "$ITERS" --threads 1 --no-cache --quiet "${MEM[@]}") ;;
      library) r=$(peak "$LIB" "$mesh" 1 "$ITERS" "$MAXMEM") ;;
      train) r=$(peak "$NEUV" train -o "$OUT/cat-$L.neuv" "$OUT/blob1-$L.obj" "$OUT/blob3-$L.obj" "$OUT/blob5-$L.obj" \
                   --iters "$ITERS" --patch-iters "$ITERS" --threads 1 --no-cache --quiet "${MEM[@]}") ;;
    esac
    kb=${r% *}; secs=${r#* }
    per=$(awk -v k="$kb" -v f="$faces" 'BEGIN { printf "%.2f", k / f }')
    [ $path = train ] && per=$(awk -v k="$kb" -v f="$faces" 'BEGIN { printf "%.2f", k / (3 * f) }')
    printf '| %d | %s | %.0f | %s | %s |\n' "$faces" "$path" "$(awk -v k="$kb" 'BEGIN { print k / 1024 }')" "$per" "$secs"
    [ -n "${first[$path]:-}" ] || first[$path]=$per
    last[$path]=$per
  done
done
summary "(train: KB per face of the three shapes together)"
