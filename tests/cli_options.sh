#!/usr/bin/env bash
# Every option of `neuv unwrap` (and of `neuv train`) either takes effect or
# is refused with exit 2 and one line naming it (issue 20): one row per
# (option, mode). Modes:
#   plain    no model: neural (NEURAL) or, where the networks play no part, the
#            cheaper LSCM run (LSCM) as the run without the option
#   save     plain with --save-model: the atlas must be the plain row's, byte
#            for byte, and the saved model must record the option
#   surface  --model SURFACE.neuv (saved by the plain --save-model row)
#   category --model CATEGORY.neuv (trained here on two tiny shapes)
#   finetune --model CATEGORY.neuv --finetune 3 (the category --finetune row's run)
#   ft+save  the same with --save-model: the atlas is the finetune run's, and
#            the saved surface model holds the fine-tuned networks (it
#            reproduces that run's UVs, not the category model's inference)
# Also neuv train: --max-distortion with --charts K refused, and what it
# stores in the model for the options it shares with unwrap.
# A row that takes effect compares the run with the mode's run without the
# option (report field, output bytes, saved model header); a refused row
# wants exit 2, one stderr line "neuv: error: ..." naming the flag, and no
# output file. Refusals that need no model are the same in every mode, so
# they get a row in the modes where someone might expect otherwise.
# The finetune mode's atlas equals ft+save's (checked), so --refine,
# --resolution and --padding are run once, with --save-model, and checked
# both in the report and in the saved model; --threads and --no-cache reach
# a fine-tuning run by the same neuv_apply_options as the category rows and
# are not run again. -o and --report are in every row. About 90 s of CPU.
set -u
NEUV="$1"
TMP="${NEUV_TEST_TMP:-/tmp}/cli_options"
rm -rf "$TMP"; mkdir -p "$TMP/pv"
pass=0; fail=0
ok()  { pass=$((pass+1)); }
bad() { fail=$((fail+1)); echo "FAIL: $*" >&2; }
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3
SECONDS=0

# Fixtures: three members of the bent-capsule family (~1000 faces each); a
# category model on two of them with few steps, auto charts, refinement 20.
for i in 0 1 2; do "$NEUV" shape bent-capsule --member $i -o "$TMP/m$i.obj" --quiet || bad "shape $i failed"; done
T="$TMP/m2.obj"
CAT="$TMP/cat.neuv"
"$NEUV" train -o "$CAT" "$TMP/m0.obj" "$TMP/m1.obj" --iters 30 --patch-iters 20 --resolution 256 --refine 20 \
  --threads 1 --quiet || bad "train failed"
# Two PatchNet patches, one network step.
NEURAL=(--charts 2 --iters 1 --resolution 128)
# The same with the paper's networks (no per-chart heads, so no solve and no
# second start that unfolds them): some charts fold, so --allow-overlaps shows.
FOLDING=(--preset paper "${NEURAL[@]}")
LSCM=(--method lscm --iters 20 --resolution 256)

# run NAME ARGS...: neuv unwrap T -o NAME.obj --report NAME.json ARGS (stdout, stderr, rc kept).
run() {
  local name="$1"; shift
  env ${RUN_ENV[@]+"${RUN_ENV[@]}"} "$NEUV" unwrap "$T" -o "$TMP/$name.obj" --report "$TMP/$name.json" --threads 1 "$@" \
    >"$TMP/$name.out" 2>"$TMP/$name.err"
  echo $? > "$TMP/$name.rc"
}
ROWS=()
RUN_ENV=()
row() { ROWS+=("$(printf '%-18s %-9s %s' "$1" "$2" "$3")"); }

# refused MODE FLAG ARGS...: exit 2, one line naming FLAG, no output written.
n=0
refused() {
  local mode="$1" flag="$2"; shift 2
  n=$((n+1))
  rm -f "$TMP/r$n.obj"
  "$NEUV" unwrap "$T" -o "$TMP/r$n.obj" --threads 1 --quiet "$@" >/dev/null 2>"$TMP/r$n.err"; local rc=$?
  if [ $rc -eq 2 ] && [ "$(wc -l < "$TMP/r$n.err")" -eq 1 ] && grep -q "^neuv: error: .*$flag" "$TMP/r$n.err" \
     && [ ! -e "$TMP/r$n.obj" ]; then ok; row "$flag" "$mode" "refused: $(sed 's/^neuv: error: //' "$TMP/r$n.err")"
  else bad "$flag ($mode): expected a one-line refusal naming $flag, got rc=$rc: $(cat "$TMP/r$n.err")"; fi
}

# effect MODE FLAG REF EXPR ARGS...: exit 0 and the Python EXPR holds over r
# (the report), ref (REF's report), same (the OBJ equals REF's byte for
# byte), quiet (nothing on stdout), cfg(path) (a saved model's header),
# sources(rep) (the charts' sources), dist(a, b) (neuv compare's largest
# UV distance between two OBJs, in the matched chart).
effect() {
  local mode="$1" flag="$2" ref="$3" expr="$4"; shift 4
  n=$((n+1))
  LAST="e$n"
  run "e$n" "$@"
  if [ "$(cat "$TMP/e$n.rc")" -ne 0 ]; then bad "$flag ($mode): exit $(cat "$TMP/e$n.rc"): $(cat "$TMP/e$n.err")"; return; fi
  if "$PY" - "$NEUV" "$TMP" "e$n" "$ref" "$expr" <<'PYEOF'; then ok; row "$flag" "$mode" "takes effect: $expr"
import json, os, subprocess, sys
neuv, tmp, name, ref_name, expr = sys.argv[1:6]
def load(n): return json.load(open(os.path.join(tmp, n + ".json")))
def cfg(p): return json.loads(json.loads(subprocess.check_output([neuv, "inspect", "--json", os.path.join(tmp, p)]))["config"])
def files(d): return sum(len(f) for _, _, f in os.walk(os.path.join(tmp, d)))
def sources(rep): return [c["source"] for c in rep["chart_list"]]
def dist(a, b):
    out = subprocess.check_output([neuv, "compare", os.path.join(tmp, a), os.path.join(tmp, b), "--json"])
    return json.loads(out)["uv_distance"]["max"]
r, ref = load(name), load(ref_name)
same = open(os.path.join(tmp, name + ".obj"), "rb").read() == open(os.path.join(tmp, ref_name + ".obj"), "rb").read()
quiet = os.path.getsize(os.path.join(tmp, name + ".out")) == 0
if not eval(expr):
    print(f"  not {expr}\n  report: method {r['method']} seed {r['seed']} threads {r['threads']} charts {r['charts']} "
          f"pack {r['pack']} refine_steps {r['param']['refine_steps']} model {r.get('model')}", file=sys.stderr)
    sys.exit(1)
PYEOF
  else bad "$flag ($mode): $expr does not hold (run e$n, against $ref)"; fi
}

# ---- the runs without the option, one per mode ----------------------------
run B --quiet "${NEURAL[@]}"
run Bf --quiet "${FOLDING[@]}"
run L --quiet "${LSCM[@]}"
run Lv "${LSCM[@]}"                       # not quiet: the --quiet row's reference
run C --quiet --model "$CAT"
for b in B Bf L Lv C; do [ "$(cat "$TMP/$b.rc")" -eq 0 ] || bad "reference run $b failed: $(cat "$TMP/$b.err")"; done

# ---- plain ------------------------------------------------------------------
effect plain --method B 'r["method"] == "lscm" and not same' --quiet "${NEURAL[@]}" --method lscm
P_METHOD=$LAST
effect plain --charts L 'r["patches"]["k"] == 3 and ref["patches"]["k"] != 3 and not same' --quiet "${LSCM[@]}" --charts 3
P_CHARTS=$LAST
effect plain --max-distortion L 'r["charts"] != ref["charts"] and not same' --quiet "${LSCM[@]}" --max-distortion 1.02
P_MAX_DISTORTION=$LAST
effect plain --preset L 'r["preset"] == "paper" and not same' --quiet "${LSCM[@]}" --preset paper
P_PRESET=$LAST
effect plain --iters L 'r["patches"]["iterations"] == 7 and not same' --quiet "${LSCM[@]}" --iters 7
P_ITERS=$LAST
effect plain --seed L 'r["seed"] == 2 and not same' --quiet "${LSCM[@]}" --seed 2
P_SEED=$LAST
effect plain --refine B 'r["param"]["refine_steps"] == 0 < ref["param"]["refine_steps"] and not same' \
  --quiet "${NEURAL[@]}" --refine 0
P_REFINE=$LAST
effect plain --resolution L 'r["pack"]["resolution"] == 512 and not same' --quiet "${LSCM[@]}" --resolution 512
P_RESOLUTION=$LAST
effect plain --padding L 'r["pack"]["padding"] == 5 and not same' --quiet "${LSCM[@]}" --padding 5
P_PADDING=$LAST
effect plain --allow-overlaps Bf '"network_folded" in sources(r) and "lscm_after_fold" in sources(ref) and not same' \
  --quiet "${FOLDING[@]}" --allow-overlaps
P_ALLOW_OVERLAPS=$LAST
effect plain --train-faces L 'r["model"]["trained_on_simplified_copy"] and "model" not in ref and not same' \
  --quiet "${LSCM[@]}" --train-faces 500
P_TRAIN_FACES=$LAST
effect plain --no-cache L 'not r["patches"]["operators_cache_hit"] and ref["patches"]["operators_cache_hit"] and same' \
  --quiet "${LSCM[@]}" --no-cache
effect plain --threads L 'r["threads"] == 2 and ref["threads"] == 1' --quiet "${LSCM[@]}" --threads 2
effect plain --quiet Lv 'quiet and os.path.getsize(os.path.join(tmp, "Lv.out")) > 0 and same' "${LSCM[@]}" --quiet
run pc --quiet "${LSCM[@]}" --preview "$TMP/pv/chart"
effect plain --preview-color pc 'open(tmp + "/pv/qce-uv.png", "rb").read() != open(tmp + "/pv/chart-uv.png", "rb").read()' \
  --quiet "${LSCM[@]}" --preview "$TMP/pv/qce" --preview-color qce
effect plain --save-model B 'same and cfg("S.neuv")["refine"] == 400 and cfg("S.neuv")["kind"] == "surface"' \
  --quiet "${NEURAL[@]}" --save-model "$TMP/S.neuv"
refused plain --max-distortion "${LSCM[@]}" --charts 3 --max-distortion 1.3
refused plain --refine "${LSCM[@]}" --refine 5
refused plain --preview-color "${LSCM[@]}" --preview-color qce
refused plain --finetune "${LSCM[@]}" --finetune 3
refused plain --check-inference "${LSCM[@]}" --check-inference
refused plain --lscm-baseline "${LSCM[@]}" --lscm-baseline
refused plain --shared-layer "${LSCM[@]}" --shared-layer
# A budget below what training this mesh needs refuses it before training
# starts (issue 20: memory); with enough budget the atlas is the plain run's.
refused plain --max-memory "${LSCM[@]}" --max-memory 1 --train-faces 0
effect plain --seam-angle L 'r["seams"]["required_edges"] == r["seams"]["above_angle"] > 0 == ref["seams"]["required_edges"] and r["seams"]["crossed"] == 0 and r["seams"]["angle"] == 10' \
  --quiet "${LSCM[@]}" --seam-angle 10
refused plain --seam-angle "${LSCM[@]}" --seam-angle 0
refused plain --seam-angle "${LSCM[@]}" --seam-angle 10 --train-faces 500
effect plain --no-hard-edges L 'r["seams"]["hard_edges"] is False and ref["seams"]["hard_edges"] is True and same' \
  --quiet "${LSCM[@]}" --no-hard-edges
effect plain --max-memory L 'same' --quiet "${LSCM[@]}" --max-memory 100000
# At 66 px per unit this shape's charts (54 px per unit in one 256 px square) need two tiles.
effect plain --texels-per-unit L 'r["pack"]["texels_per_unit"] == 66 and len(r["tiles"]) >= 2 and [t["udim"] for t in r["tiles"]] == list(range(1001, 1001 + len(r["tiles"]))) and [t["udim"] for t in ref["tiles"]] == [1001] and r["metrics"]["overlap_fraction"] == 0' \
  --quiet "${LSCM[@]}" --texels-per-unit 66
refused plain --texels-per-unit "${LSCM[@]}" --texels-per-unit 0
refused plain --texels-per-unit "${LSCM[@]}" --texels-per-unit 1000

# ---- save: the plain row's atlas, the option in the model -------------------
effect save --method "$P_METHOD" 'same and cfg("s1.neuv")["method"] == "lscm"' \
  --quiet "${NEURAL[@]}" --method lscm --save-model "$TMP/s1.neuv"
effect save --charts "$P_CHARTS" 'same' --quiet "${LSCM[@]}" --charts 3 --save-model "$TMP/s2.neuv"
effect save --max-distortion "$P_MAX_DISTORTION" 'same' --quiet "${LSCM[@]}" --max-distortion 1.02 --save-model "$TMP/s3.neuv"
effect save --preset "$P_PRESET" 'same and cfg("s4.neuv")["preset"] == "paper"' \
  --quiet "${LSCM[@]}" --preset paper --save-model "$TMP/s4.neuv"
effect save --iters "$P_ITERS" 'same' --quiet "${LSCM[@]}" --iters 7 --save-model "$TMP/s5.neuv"
effect save --seed "$P_SEED" 'same and cfg("s6.neuv")["seed"] == 2' --quiet "${LSCM[@]}" --seed 2 --save-model "$TMP/s6.neuv"
effect save --refine "$P_REFINE" 'same and cfg("s7.neuv")["refine"] == 0' \
  --quiet "${NEURAL[@]}" --refine 0 --save-model "$TMP/s7.neuv"
effect save --resolution "$P_RESOLUTION" 'same and cfg("s8.neuv")["resolution"] == 512' \
  --quiet "${LSCM[@]}" --resolution 512 --save-model "$TMP/s8.neuv"
effect save --padding "$P_PADDING" 'same and cfg("s9.neuv")["padding"] == 5' \
  --quiet "${LSCM[@]}" --padding 5 --save-model "$TMP/s9.neuv"
effect save --allow-overlaps "$P_ALLOW_OVERLAPS" 'same' --quiet "${FOLDING[@]}" --allow-overlaps --save-model "$TMP/s10.neuv"
# A model saved with --train-faces is the full mesh's atlas (the copy's layout is nobody's texture).
effect save --train-faces "$P_TRAIN_FACES" 'same and cfg("s11.neuv")["source_faces"] == r["faces"] and r["model"]["trained_on_simplified_copy"]' \
  --quiet "${LSCM[@]}" --train-faces 500 --save-model "$TMP/s11.neuv"
effect save --no-cache L 'same and not r["patches"]["operators_cache_hit"]' \
  --quiet "${LSCM[@]}" --no-cache --save-model "$TMP/s12.neuv"
effect save --threads L 'same and r["threads"] == 2' --quiet "${LSCM[@]}" --threads 2 --save-model "$TMP/s13.neuv"
effect save --quiet Lv 'same and quiet' "${LSCM[@]}" --quiet --save-model "$TMP/s14.neuv"
refused save --finetune "${LSCM[@]}" --finetune 3 --save-model "$TMP/x.neuv"
refused save --check-inference "${LSCM[@]}" --check-inference --save-model "$TMP/x.neuv"
refused save --lscm-baseline "${LSCM[@]}" --lscm-baseline --save-model "$TMP/x.neuv"
refused save --shared-layer "${LSCM[@]}" --shared-layer --save-model "$TMP/x.neuv"
refused save --seam-angle "${LSCM[@]}" --seam-angle 10 --save-model "$TMP/x.neuv"
refused save --texels-per-unit "${LSCM[@]}" --texels-per-unit 66 --save-model "$TMP/x.neuv"
effect save --no-hard-edges L 'same and r["seams"]["hard_edges"] is False' --quiet "${LSCM[@]}" --no-hard-edges \
  --save-model "$TMP/s15.neuv"
[ ! -e "$TMP/x.neuv" ] && ok || bad "a refused --save-model left $TMP/x.neuv"

# ---- surface ------------------------------------------------------------------
S="$TMP/S.neuv"
run SA --quiet --model "$S"
[ "$(cat "$TMP/SA.rc")" -eq 0 ] || bad "applying the surface model failed: $(cat "$TMP/SA.err")"
RUN_ENV=(XDG_CACHE_HOME="$TMP/cacheA")  # operators computed and cached here
effect surface --check-inference SA 'r["model"]["patchnet_label_agreement"] is not None and ref["model"]["patchnet_label_agreement"] is None' \
  --quiet --model "$S" --check-inference
S_CHECK=$LAST
RUN_ENV=()
effect surface --lscm-baseline SA 'r["model"]["network_charts"] == 0 < ref["model"]["network_charts"] and not same' \
  --quiet --model "$S" --lscm-baseline
# A surface model computes operators only for --check-inference, each run
# here on a fresh cache folder (a miss either way), so the cache is seen on disk.
RUN_ENV=(XDG_CACHE_HOME="$TMP/cacheB")
effect surface --no-cache "$S_CHECK" 'files("cacheB") == 0 < files("cacheA") and r["model"]["patchnet_label_agreement"] == ref["model"]["patchnet_label_agreement"]' \
  --quiet --model "$S" --check-inference --no-cache
RUN_ENV=()
effect surface --threads SA 'r["threads"] == 2 and same' --quiet --model "$S" --threads 2
effect surface --quiet SA 'quiet and same' --model "$S" --quiet
for a in "--method lscm" "--preset paper" "--charts 3" "--max-distortion 1.3" "--iters 5" "--seed 2" "--train-faces 500" "--max-memory 100" \
         "--resolution 512" "--padding 5" "--refine 0" "--allow-overlaps" "--finetune 3" "--shared-layer" \
         "--seam-angle 10" "--no-hard-edges" "--texels-per-unit 66" "--save-model $TMP/x.neuv"; do
  refused surface "${a%% *}" --model "$S" $a
done
[ ! -e "$TMP/x.neuv" ] && ok || bad "a refused --save-model left $TMP/x.neuv"

# ---- category (inference) -----------------------------------------------------
effect category --refine C 'r["param"]["refine_steps"] == 0 < ref["param"]["refine_steps"] and not same' \
  --quiet --model "$CAT" --refine 0
effect category --resolution C 'r["pack"]["resolution"] == 512 and ref["pack"]["resolution"] == 256 and not same' \
  --quiet --model "$CAT" --resolution 512
effect category --padding C 'r["pack"]["padding"] == 5 and not same' --quiet --model "$CAT" --padding 5
# --allow-overlaps needs charts that fold: a second category model with two
# patches (big charts) and three network steps, inferred through its shared
# output layer, where every chart folds (10 of 10 measured; with a head per
# chart how many fold, and whether the repair is a re-flattening or a split,
# changed with the OpenBLAS kernel).
"$NEUV" train -o "$TMP/cat2.neuv" "$TMP/m0.obj" "$TMP/m1.obj" --charts 2 --iters 3 --patch-iters 20 --resolution 256 \
  --refine 20 --threads 1 --quiet || bad "train (two patches) failed"
run C2 --quiet --model "$TMP/cat2.neuv" --shared-layer
effect category --allow-overlaps C2 '"network_folded" in sources(r) and "network_folded" not in sources(ref) and {"lscm_after_fold", "lscm_after_split"} & set(sources(ref)) and not same' \
  --quiet --model "$TMP/cat2.neuv" --shared-layer --allow-overlaps
effect category --shared-layer C 'r["model"]["output_layer"] == "shared" and not same' --quiet --model "$CAT" --shared-layer
effect category --finetune C 'r["model"]["finetune_steps"] == 3 and ref["model"]["finetune_steps"] == 0 and not same' \
  --quiet --model "$CAT" --finetune 3
F=$LAST  # the finetune mode's run without further options
effect category --no-cache C 'not r["patches"]["operators_cache_hit"] and ref["patches"]["operators_cache_hit"] and same' \
  --quiet --model "$CAT" --no-cache
effect category --threads C 'r["threads"] == 2' --quiet --model "$CAT" --threads 2
for a in "--method lscm" "--preset paper" "--charts 3" "--max-distortion 1.3" "--iters 5" "--seed 2" "--train-faces 500" "--max-memory 100" \
         "--check-inference" "--lscm-baseline" "--seam-angle 10" "--no-hard-edges" "--texels-per-unit 66" "--save-model $TMP/x.neuv"; do
  refused category "${a%% *}" --model "$CAT" $a
done
[ ! -e "$TMP/x.neuv" ] && ok || bad "a refused --save-model left $TMP/x.neuv"

# ---- finetune, and finetune with --save-model ---------------------------------
effect ft+save --save-model "$F" 'same and cfg("FT.neuv")["kind"] == "surface" and cfg("FT.neuv")["refine"] == 20' \
  --quiet --model "$CAT" --finetune 3 --save-model "$TMP/FT.neuv"
# The saved model holds the fine-tuned networks: applied to the same shape it
# gives the fine-tuned run's UVs from the networks themselves, which the
# category model's inference does not.
effect "ft+save:apply" --save-model "$F" 'dist(ref_name + ".obj", name + ".obj") < 1e-9 and dist("C.obj", name + ".obj") > 1e-3 and r["model"]["network_charts"] == r["charts"]' \
  --quiet --model "$TMP/FT.neuv"
"$PY" - "$NEUV" "$CAT" "$TMP/FT.neuv" <<'PYEOF' && ok || bad "the saved model's networks are the category model's, not fine-tuned"
import json, subprocess, sys
neuv, cat, ft = sys.argv[1:4]
def weights(p):
    d = json.loads(subprocess.check_output([neuv, "inspect", "--json", p]))
    return {t["name"]: t["rms"] for t in d["tensors"] if t["name"].startswith(("f.", "g."))}
a, b = weights(cat), weights(ft)
assert set(a) == set(b) and a, (sorted(a), sorted(b))
assert any(a[k] != b[k] for k in a), "identical weights"
PYEOF
effect ft+save --refine "$F" 'r["param"]["refine_steps"] == 0 and cfg("FT2.neuv")["refine"] == 0 and not same' \
  --quiet --model "$CAT" --finetune 3 --refine 0 --save-model "$TMP/FT2.neuv"
effect ft+save --resolution "$F" 'r["pack"]["resolution"] == 512 and cfg("FT3.neuv")["resolution"] == 512 and not same' \
  --quiet --model "$CAT" --finetune 3 --resolution 512 --save-model "$TMP/FT3.neuv"
effect ft+save --padding "$F" 'r["pack"]["padding"] == 5 and cfg("FT4.neuv")["padding"] == 5 and not same' \
  --quiet --model "$CAT" --finetune 3 --padding 5 --save-model "$TMP/FT4.neuv"
# No chart of this shape folds after fine-tuning, so --allow-overlaps has
# nothing to keep here (it is passed through as in the category rows).
effect finetune --allow-overlaps "$F" 'r["model"]["finetune_steps"] == 3 and sources(r) == sources(ref)' \
  --quiet --model "$CAT" --finetune 3 --allow-overlaps
for a in "--shared-layer" "--check-inference" "--lscm-baseline" "--method lscm" "--preset paper" "--charts 3" \
         "--max-distortion 1.3" "--iters 5" "--seed 2" "--train-faces 500" "--max-memory 100"; do
  refused finetune "${a%% *}" --model "$CAT" --finetune 3 $a
  refused ft+save "${a%% *}" --model "$CAT" --finetune 3 --save-model "$TMP/x.neuv" $a
done
[ ! -e "$TMP/x.neuv" ] && ok || bad "a refused --save-model left $TMP/x.neuv"

# ---- neuv train: what it stores -----------------------------------------------
TR=(-o "$TMP/t.neuv" "$TMP/m0.obj" --iters 10 --patch-iters 10 --threads 1 --quiet)
"$NEUV" train "${TR[@]}" --charts 3 --max-distortion 1.3 2>"$TMP/t.err"; rc=$?
[ $rc -eq 2 ] && [ "$(wc -l < "$TMP/t.err")" -eq 1 ] && grep -q -- "--max-distortion" "$TMP/t.err" && ok \
  || bad "train --charts 3 --max-distortion: rc=$rc $(cat "$TMP/t.err")"
row --max-distortion train "refused with --charts K: $(sed 's/^neuv: error: //' "$TMP/t.err")"
rm -f "$TMP/t.neuv"
"$NEUV" train "${TR[@]}" --max-memory 1 2>"$TMP/t.err"; rc=$?
[ $rc -eq 2 ] && [ "$(wc -l < "$TMP/t.err")" -eq 1 ] && grep -q -- "--max-memory" "$TMP/t.err" && [ ! -e "$TMP/t.neuv" ] && ok \
  || bad "train --max-memory 1: rc=$rc $(cat "$TMP/t.err")"
row --max-memory train "a budget below the estimate refuses: $(sed 's/^neuv: error: //' "$TMP/t.err")"
for a in "--resolution 512:resolution:512" "--padding 5:padding:5" "--refine 0:refine:0" "--seed 2:seed:2" \
         "--max-distortion 1.3:max_distortion:1.3" "--charts 3:charts_auto:0"; do
  IFS=: read -r opt key want <<<"$a"
  if "$NEUV" train "${TR[@]}" $opt && "$PY" - "$NEUV" "$TMP/t.neuv" "$key" "$want" <<'PYEOF'; then ok; row "${opt%% *}" train "stored: $key $want"
import json, subprocess, sys
neuv, p, key, want = sys.argv[1:5]
c = json.loads(json.loads(subprocess.check_output([neuv, "inspect", "--json", p]))["config"])
assert float(c[key]) == float(want), (key, c.get(key), want)
PYEOF
  else bad "train $opt: model header has not $key $want"; fi
done

echo "cli_options: the table (option, mode, outcome)"
printf '%s\n' "${ROWS[@]}"
echo "cli_options: $pass passed, $fail failed, ${SECONDS} s"
[ $fail -eq 0 ]
