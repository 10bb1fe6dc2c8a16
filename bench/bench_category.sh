#!/usr/bin/env bash
# Issue 8 bench: a category model. Members 0-19 of the procedural bent-capsule
# family (`neuv shape bent-capsule --member I`) train one model
# (`neuv train`); members 20-24, never seen, are unwrapped with it by
# inference (`neuv unwrap --model`), and by per-shape training (`neuv unwrap`)
# for comparison. Both with the vertex refinement off (--refine 0: the
# networks' map itself, plus repairs) and with the defaults (refinement on).
# FAMILY=blob runs the same on the second family (`neuv shape blob`).
# Usage: [FAMILY=bent-capsule|blob] bench/bench_category.sh BUILD_DIR [OUT_DIR] [extra neuv train options]
set -eu
B="$1"; OUT="${2:-/tmp/bench_category}"; NEUV="$B/neuv"; FAMILY="${FAMILY:-bent-capsule}"
shift; [ $# -gt 0 ] && shift
mkdir -p "$OUT"
for i in $(seq 0 24); do "$NEUV" shape "$FAMILY" --member "$i" -o "$OUT/m$i.obj" --quiet; done
train=()
for i in $(seq 0 19); do train+=("$OUT/m$i.obj"); done
"$NEUV" train -o "$OUT/family.neuv" "${train[@]}" --report "$OUT/train.json" --quiet "$@"
for i in $(seq 20 24); do
  for r in 0 default; do
    ropt=(); [ "$r" = 0 ] && ropt=(--refine 0)
    "$NEUV" unwrap "$OUT/m$i.obj" --model "$OUT/family.neuv" "${ropt[@]}" -o "$OUT/cat-$r-$i.obj" \
      --report "$OUT/cat-$r-$i.json" --quiet
    "$NEUV" unwrap "$OUT/m$i.obj" "${ropt[@]}" -o "$OUT/own-$r-$i.obj" --report "$OUT/own-$r-$i.json" --quiet
  done
done
python3 - "$OUT" <<'PY'
import json, sys, statistics
out = sys.argv[1]
t = json.load(open(f"{out}/train.json"))
print(f"trained on {t['shapes']} shapes ({t['faces']} faces, {t['charts']} charts): PatchNet {t['patchnet_iterations']} steps, "
      f"networks {t['param_iterations']} steps, {t['seconds']['total']:.1f} s")
print("| member | faces | refine | charts cat/own | qce_mean category | qce_mean per-shape | ratio | category chart sources | network area | network qce | LSCM qce (same charts) | flipped | overlap | s category / per-shape |")
print("|---|---:|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|")
ratios = {"0": [], "default": []}
for r in ("0", "default"):
    for i in range(20, 25):
        c = json.load(open(f"{out}/cat-{r}-{i}.json")); o = json.load(open(f"{out}/own-{r}-{i}.json"))
        q, qo = c["metrics"]["qce_mean"], o["metrics"]["qce_mean"]
        ratios[r].append(q / qo)
        pv = c["provenance"]
        src = ", ".join(f"{v['charts']} {k}" for k, v in pv["sources"].items() if v["charts"] > 0)
        nq, lq = pv["network_qce_mean"], pv["lscm_qce_mean_same_charts"]
        f4 = lambda v: "–" if v is None else f"{v:.4f}"
        print(f"| {i} | {c['faces']} | {r} | {c['charts']}/{o['charts']} | {q:.4f} | {qo:.4f} | {q/qo:.3f} | "
              f"{src} | {pv['network_area_fraction']:.3f} | {f4(nq)} | {f4(lq)} | {c['metrics']['flipped']} | "
              f"{c['metrics']['overlap_fraction']:.2g} | {c['seconds']['total']:.1f} / {o['seconds']['total']:.1f} |")
for r in ratios:
    print(f"refine {r}: category / per-shape qce_mean: worst {max(ratios[r]):.3f}, mean {statistics.mean(ratios[r]):.3f}")
PY
