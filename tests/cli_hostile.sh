#!/usr/bin/env bash
# Hostile meshes through `neuv unwrap` (issue 20, item 6). The test writes every
# mesh itself (tests/hostile_gen.py, standard library only), then runs
#   neuv unwrap IN -o OUT --report R.json --threads 1 [--method ...]
# under `timeout BOUND` (one thread: ctest runs two tests at once, and two
# threads each on 2 cores made the neural path's many short parallel regions
# wait on descheduled threads: the 528-face sphere of huge_coords took 71 s
# with 2 threads on a busy machine, 19 s with 1, past its 60 s bound once),
# and requires, for each case, one of two outcomes:
#   ok:      exit 0, OUT written, the report's metrics.flipped == 0 and
#            metrics.overlap_fraction == 0, and the same from `neuv eval --json OUT`
#            (eval skipped on the large mesh, where the report is used);
#   refused: exit 2, exactly one line on stderr, `neuv: error: IN: message`,
#            and no OUT (nor OUT.tmp-*) left behind.
# Anything else fails: a crash (134, 139), a timeout (124), exit 1, flips,
# overlaps. Some cases must be one of the two (the "expect" column: any, ok,
# refused; "known": should be ok, but a refusal is a known bug, reported and
# not counted).
#
# Case                 | mesh                                           | method | bound  | expect  | outcome, time (2-core machine, busy)
# ---------------------|------------------------------------------------|--------|--------|---------|-------------------------------------
# nonmanifold_edge     | grid, 2 fins on one edge (4 faces on it)       | neural |   60 s | any     | ok, 7 s
# nonmanifold_vertex   | two open cones sharing their apex              | neural |   60 s | any     | ok, 8 s
# zero_area            | grid + collinear, coincident, one-point faces  | neural |   60 s | any     | ok, 5 s
# duplicate            | grid, every 10th face again (half reversed)    | neural |   60 s | any     | ok, 7 s
# isolated             | grid + 500 vertices no face uses               | neural |   60 s | ok      | ok, 7 s
# huge_coords          | closed sphere of radius 1e30                   | neural |   60 s | ok      | ok, 17-22 s (was exit 1, fixed)
# tiny_coords          | closed sphere of radius 1e-30                  | neural |   60 s | ok      | ok, 18-23 s (was exit 1, fixed)
# huge_offset          | unit grid at (1e8, 1e8, 1e8)                   | lscm   |   60 s | any     | ok, <1 s
# nan                  | OBJ with a NaN coordinate                      | neural |   30 s | refused | refused, <1 s
# inf                  | OFF with an Inf coordinate                     | neural |   30 s | refused | refused, <1 s
# nan_binary           | binary PLY with a NaN coordinate               | neural |   30 s | refused | refused, <1 s
# single               | one triangle                                   | neural |   60 s | ok      | ok, 5 s
# degenerate_polygons  | grid + polygons with repeated/collinear corners| neural |   60 s | any     | ok, 6 s
# only_degenerate      | nothing but zero-area faces                    | neural |   30 s | refused | refused, <1 s
# components           | 1000 tiny closed tetrahedra (2000 charts)      | neural |  120 s | ok      | ok, 60-92 s (was past 300 s)
# large (CI)           | bumpy grid, binary PLY, 60k faces              | lscm   |  120 s | ok      | ok, 15 s
# large (opt-in)       | the same grid at 2M faces (the issue's figure) | lscm   | 1800 s | ok      | ok, 99-117 s, 974 MB peak (was refused)
#
# The whole script takes 193 s here (another test run sharing the 2 cores;
# 126 s when components ran with --method lscm);
# writing the 2M-face PLY takes 3 s; with NEUV_HOSTILE_LARGE=1 it took 191 s
# before components ran the neural method (some 55 s more now).
#
# Known failures (bugs found; both fixed now, kept for the record):
# (1, fixed) Grids of 200k faces and more were refused after ~100 s with
#    "eigen solver converged for 52 of 64 eigenpairs after 1001 restarts":
#    above 20k faces unwrap trains on a simplified copy, meshoptimizer's
#    simplifier (no link condition) tore the grid (200k faces -> 9
#    components, 9 holes), and ARPACK did not converge on that copy. The
#    copy's topology is now checked against the input's, and a torn copy is
#    made again by CGAL's edge collapse (src/remesh/simplify.c,
#    edge_collapse.cpp). NEUV_HOSTILE_LARGE=1 runs the 2M-face case (expect
#    ok); NEUV_HOSTILE_LARGE_FACES=N picks another size.
# (2, fixed) The default (neural) method on the 1000 components ran past
#    300 s: two per-chart costs did not shrink with the chart. The heads'
#    Gauss-Newton solve (param_output_solve_heads) solved 2(H+1) = 840
#    unknowns per chart and step; a chart with fewer vertices than features
#    now takes the same step in vertex space (2 #V unknowns, push-through
#    identity, src/models/param_output_solve.c dual_eq). The refinement ran
#    400 Adam steps per chart, 0.16 s a two-face chart (310 s in all); pieces
#    of at most 16 faces are now refined together in one run
#    (src/unwrap/unwrap.c, refine_pieces_together). 2000 charts now take
#    60-92 s at one thread, most of it the networks' training (proportional
#    to the faces) and the packing; every chart stays the networks'
#    (network+refined), 0 flipped, 0 overlap.
#
# Usage: cli_hostile.sh /path/to/neuv
set -u
NEUV=${1:?usage: cli_hostile.sh /path/to/neuv}
HERE=$(cd "$(dirname "$0")" && pwd)
GEN="$HERE/hostile_gen.py"
TMP=${NEUV_TEST_TMP:-/tmp}/cli_hostile
rm -rf "$TMP"; mkdir -p "$TMP"
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
pass=0; fail=0; known=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }
T0=$(date +%s)

# The metrics of a report (metrics.*) or of `neuv eval --json` (metrics.*):
# prints "flipped overlap_fraction" or nothing when the file is not that JSON.
flips_overlap() {
    "$PY" - "$1" <<'PYEOF'
import json, sys
m = json.load(open(sys.argv[1]))["metrics"]
print(m["flipped"], m["overlap_fraction"])
PYEOF
}

# run_case NAME EXT EXPECT BOUND [unwrap options...]
run_case() {
    local name=$1 ext=$2 expect=$3 bound=$4
    shift 4
    local in="$TMP/$name.$ext" out="$TMP/out-$name.obj" rep="$TMP/$name.json" err="$TMP/$name.err"
    local size=""
    [ "$name" = large ] && size=$LARGE_FACES
    if ! "$PY" "$GEN" "$name" "$in" $size; then bad "$name: could not write the mesh"; return; fi
    local t1 t2 rc
    t1=$(date +%s.%N)
    timeout -k 10 "$bound" "$NEUV" unwrap "$in" -o "$out" --report "$rep" --threads 1 --quiet "$@" 2>"$err" >/dev/null
    rc=$?
    t2=$(date +%s.%N)
    local secs
    secs=$("$PY" -c "print('%.1f' % ($t2 - $t1))")
    case $rc in
    0)
        echo "$name: ok in $secs s (bound $bound s)"
        [ "$expect" = refused ] && bad "$name: expected a refusal (exit 2), got exit 0"
        [ "$expect" = known ] && echo "$name: the known failure is gone: make this case expect ok"
        [ -s "$out" ] && ok || bad "$name: exit 0 but $out is missing or empty"
        local fo
        fo=$(flips_overlap "$rep") || { bad "$name: the report has no metrics.flipped / overlap_fraction"; return; }
        [ "$fo" = "0 0" ] && ok || bad "$name: report says flipped / overlap_fraction = $fo, expected 0 0"
        if [ "$name" != large ] && [ -s "$out" ]; then
            if "$NEUV" eval "$out" --json >"$TMP/$name.eval.json" 2>"$TMP/$name.eval.err"; then
                fo=$(flips_overlap "$TMP/$name.eval.json")
                [ "$fo" = "0 0" ] && ok || bad "$name: neuv eval says flipped / overlap_fraction = $fo, expected 0 0"
            else
                bad "$name: neuv eval of the output failed: $(cat "$TMP/$name.eval.err")"
            fi
        fi
        ;;
    2)
        local lines msg
        lines=$(grep -c '' "$err")
        msg=$(cat "$err")
        echo "$name: refused in $secs s: $msg"
        [ "$expect" = ok ] && bad "$name: expected an unwrap, got a refusal: $msg"
        if [ "$expect" = known ]; then
            echo "$name: KNOWN FAILURE (not counted): should unwrap, but was refused (see the header)"
            known=$((known + 1))
        fi
        [ "$lines" -eq 1 ] && ok || bad "$name: $lines lines on stderr, expected 1: $msg"
        case "$msg" in
            "neuv: error: $in: "?*) ok ;;
            *) bad "$name: stderr does not start with 'neuv: error: $in: ': $msg" ;;
        esac
        [ ! -e "$out" ] && ok || bad "$name: refused but $out was written"
        if ls "$out".tmp-* >/dev/null 2>&1; then bad "$name: temporary file left behind"; else ok; fi
        [ ! -e "$rep" ] && ok || bad "$name: refused but the report $rep was written"
        ;;
    124 | 137)
        bad "$name: ran past its bound of $bound s (exit $rc)" ;;
    *)
        bad "$name: exit $rc after $secs s (crash or internal error): $(head -c 400 "$err")" ;;
    esac
}

if [ "${NEUV_HOSTILE_LARGE:-0}" = 1 ]; then
    LARGE_FACES=${NEUV_HOSTILE_LARGE_FACES:-2000000}; LARGE_BOUND=1800; LARGE_EXPECT=ok
else
    LARGE_FACES=${NEUV_HOSTILE_LARGE_FACES:-60000}; LARGE_BOUND=120; LARGE_EXPECT=ok
fi

run_case nonmanifold_edge    obj any     60
run_case nonmanifold_vertex  obj any     60
run_case zero_area           obj any     60
run_case duplicate           obj any     60
run_case isolated            obj ok      60
run_case huge_coords         obj ok      60
run_case tiny_coords         obj ok      60
run_case huge_offset         obj any     60 --method lscm
run_case nan                 obj refused 30
run_case inf                 off refused 30
run_case nan_binary          ply refused 30
run_case single              obj ok      60
run_case degenerate_polygons obj any     60
run_case only_degenerate     obj refused 30
run_case components          obj ok      120
echo "large: $LARGE_FACES faces"
run_case large               ply "$LARGE_EXPECT" "$LARGE_BOUND" --method lscm

echo "cli_hostile: $pass passed, $fail failed, $known known failures, $(( $(date +%s) - T0 )) s"
[ "$fail" -eq 0 ]
