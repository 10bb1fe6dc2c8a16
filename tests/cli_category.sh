#!/usr/bin/env bash
# Category models (issue 8): `neuv train` on four members of the procedural
# bent-capsule family, `neuv unwrap --model` on an unseen member by
# inference and with --finetune; the guarantees hold, the outputs are
# deterministic, and bad input exits 2 with one line. Quality against
# per-shape training is measured by bench/bench_category.sh.
set -u
NEUV="$1"
TMP="${NEUV_TEST_TMP:-/tmp}/cli_category"
rm -rf "$TMP"; mkdir -p "$TMP"
pass=0; fail=0
ok()  { pass=$((pass+1)); }
bad() { fail=$((fail+1)); echo "FAIL: $*" >&2; }
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3

for i in 0 1 2 3 30; do
  "$NEUV" shape bent-capsule --member $i -o "$TMP/m$i.obj" --quiet && ok || bad "shape member $i failed"
done
cmp -s "$TMP/m0.obj" "$TMP/m1.obj" && bad "members 0 and 1 are the same shape" || ok

TRAIN=(--iters 150 --patch-iters 60 --threads 1 --quiet)
"$NEUV" train -o "$TMP/c.neuv" "$TMP"/m{0,1,2,3}.obj --report "$TMP/train.json" "${TRAIN[@]}" && ok || bad "train failed"
"$NEUV" train -o "$TMP/c2.neuv" "$TMP"/m{0,1,2,3}.obj "${TRAIN[@]}" && ok || bad "second train failed"
cmp -s "$TMP/c.neuv" "$TMP/c2.neuv" && ok || bad "training is not deterministic"
"$PY" - "$TMP/train.json" <<'PYEOF' && ok || bad "train report"
import json, sys
t = json.load(open(sys.argv[1]))
assert t["shapes"] == 4 and t["patchnet_iterations"] <= 60 and t["param_iterations"] == 150, t
assert t["charts"] >= 4 and t["param_loss"] > 0, t
PYEOF

# unwrap_check OBJ REPORT FINETUNE label: the guarantees and the report's model section.
unwrap_check() {
  "$NEUV" eval "$1" --json > "$TMP/eval.json" 2>/dev/null || { bad "$4: eval failed"; return; }
  "$PY" - "$1" "$2" "$TMP/eval.json" "$3" <<'PYEOF' && ok || bad "$4: guarantee or report broken"
import json, sys
obj, rep, ev, finetune = sys.argv[1:5]
e = json.load(open(ev))["metrics"]; r = json.load(open(rep))
assert e["flipped"] == 0 and e["overlap_fraction"] == 0, e
assert abs(e["qce_mean"] - r["metrics"]["qce_mean"]) < 1e-9, (e, r["metrics"])
m = r["model"]
assert m["kind"] == "category" and m["finetune_steps"] == int(finetune), m
assert 1 <= m["network_charts"] <= r["charts"], m
uv = [list(map(float, l.split()[1:3])) for l in open(obj) if l.startswith("vt ")]
assert uv and all(0 <= a <= 1 and 0 <= b <= 1 for a, b in uv)
PYEOF
}
"$NEUV" unwrap "$TMP/m30.obj" --model "$TMP/c.neuv" -o "$TMP/u.obj" --report "$TMP/u.json" --threads 1 --quiet \
  && ok || bad "unwrap --model (category) failed"
unwrap_check "$TMP/u.obj" "$TMP/u.json" 0 inference
"$NEUV" unwrap "$TMP/m30.obj" --model "$TMP/c.neuv" -o "$TMP/u2.obj" --threads 1 --quiet && ok || bad "second unwrap failed"
cmp -s "$TMP/u.obj" "$TMP/u2.obj" && ok || bad "category inference is not deterministic"
"$NEUV" unwrap "$TMP/m30.obj" --model "$TMP/c.neuv" --refine 0 --finetune 20 -o "$TMP/f.obj" --report "$TMP/f.json" \
  --threads 1 --quiet && ok || bad "unwrap --finetune failed"
unwrap_check "$TMP/f.obj" "$TMP/f.json" 20 finetune

# The networks' own map on the unseen member (--refine 0): with a head per
# chart solved on this shape (the default) against the shared output layer.
for mode in heads shared; do
  extra=(); [ $mode = shared ] && extra=(--shared-layer)
  "$NEUV" unwrap "$TMP/m30.obj" --model "$TMP/c.neuv" --refine 0 "${extra[@]}" -o "$TMP/n-$mode.obj" \
    --report "$TMP/n-$mode.json" --threads 1 --quiet && ok || bad "unwrap --refine 0 ($mode) failed"
done
"$PY" - "$TMP/n-heads.json" "$TMP/n-shared.json" <<'PYEOF' && ok || bad "heads solved on the unseen shape"
import json, sys
h, s = (json.load(open(p)) for p in sys.argv[1:3])
assert h["model"]["output_layer"] == "a head per chart, solved on this shape", h["model"]
assert s["model"]["output_layer"] == "shared", s["model"]
def ratio(r):
    p = r["provenance"]
    return p["network_area_fraction"], p["network_qce_mean"] / p["lscm_qce_mean_same_charts"]
(ha, hr), (sa, sr) = ratio(h), ratio(s)
print(f"heads: network area {ha:.3f}, qce ratio to LSCM {hr:.4f}; shared layer: {sa:.3f}, {sr:.4f}")
# Measured (150 training steps, 4 members), one machine, three OpenBLAS kernels:
# heads area 1.000 and ratio 1.0011 (default kernel), 1.0182 (OPENBLAS_CORETYPE=
# Haswell), 1.0462 (CI's run); shared layer 0.05-0.08 and 1.26-1.40. A model this
# small moves by a few percent with the last bits of sgemm, so the bound here
# separates the heads from the shared layer with room for that; the issue's 3%
# bar is measured by bench/bench_category.sh (20 members, 1600 steps): 0.999-1.001.
# With PatchNet's hks+normals input (2026-12-06) the shared layer maps all of
# this small model's charts injectively too (area 1.000, ratio 1.31 against the
# heads' 1.0000), so the area no longer separates them; the ratio does.
assert ha >= 0.9 and hr <= 1.08, (ha, hr)
assert ha >= sa, (ha, sa)
assert hr < sr, (hr, sr)
PYEOF

expect_2() {
  local label="$1"; shift
  "$@" >/dev/null 2>"$TMP/err"; local rc=$?
  if [ $rc -eq 2 ] && [ "$(wc -l < "$TMP/err")" -eq 1 ] && grep -q "^neuv: error: " "$TMP/err"; then ok
  else bad "$label: rc=$rc stderr=$(cat "$TMP/err")"; fi
}
expect_2 "train without inputs" "$NEUV" train -o "$TMP/x.neuv"
expect_2 "train without -o" "$NEUV" train "$TMP/m0.obj"
expect_2 "train missing input" "$NEUV" train -o "$TMP/x.neuv" "$TMP/m0.obj" "$TMP/none.obj"
expect_2 "train onto an input" "$NEUV" train -o "$TMP/m0.obj" "$TMP/m0.obj" "$TMP/m1.obj"
expect_2 "train --charts 0" "$NEUV" train -o "$TMP/x.neuv" "$TMP/m0.obj" --charts 0
expect_2 "train --preset" "$NEUV" train -o "$TMP/x.neuv" "$TMP/m0.obj" --preset slow
expect_2 "train unknown option" "$NEUV" train -o "$TMP/x.neuv" "$TMP/m0.obj" --method lscm
printf "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n" > "$TMP/flat.obj"
expect_2 "train degenerate shape" "$NEUV" train -o "$TMP/x.neuv" "$TMP/m0.obj" "$TMP/flat.obj" --quiet
[ ! -e "$TMP/x.neuv" ] && ok || bad "a failed train left $TMP/x.neuv"
expect_2 "check-inference with a category model" "$NEUV" unwrap "$TMP/m30.obj" --model "$TMP/c.neuv" \
  --check-inference -o "$TMP/x.obj"
expect_2 "negative finetune" "$NEUV" unwrap "$TMP/m30.obj" --model "$TMP/c.neuv" --finetune -1 -o "$TMP/x.obj"
expect_2 "finetune without a model" "$NEUV" unwrap "$TMP/m30.obj" --finetune 5 -o "$TMP/x.obj"
# Inference trains nothing of this shape's to save (with --finetune it saves the
# fine-tuned networks: tests/cli_options.sh).
expect_2 "save-model with a category model, no finetune" "$NEUV" unwrap "$TMP/m30.obj" --model "$TMP/c.neuv" \
  --save-model "$TMP/x.neuv" -o "$TMP/x.obj"
[ ! -e "$TMP/x.neuv" ] && ok || bad "a refused --save-model left $TMP/x.neuv"
expect_2 "shared-layer without a model" "$NEUV" unwrap "$TMP/m30.obj" --shared-layer -o "$TMP/x.obj"
expect_2 "shared-layer with finetune" "$NEUV" unwrap "$TMP/m30.obj" --model "$TMP/c.neuv" --shared-layer \
  --finetune 5 -o "$TMP/x.obj"
[ ! -e "$TMP/x.obj" ] && ok || bad "a failed unwrap left $TMP/x.obj"
expect_2 "shape without member" "$NEUV" shape bent-capsule -o "$TMP/s.obj"
expect_2 "shape unknown" "$NEUV" shape teapot -o "$TMP/s.obj"
expect_2 "shape member on a fixed shape" "$NEUV" shape sphere --member 3 -o "$TMP/s.obj"
[ ! -e "$TMP/s.obj" ] && ok || bad "a failed shape left $TMP/s.obj"

echo "cli_category: $pass passed, $fail failed"
[ $fail -eq 0 ]
