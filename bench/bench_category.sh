#!/usr/bin/env bash
# Issue 8 bench: a category model. Members 0-19 of the procedural bent-capsule
# family (`neuv shape bent-capsule --member I`) train one model
# (`neuv train`); members 20-24, never seen, are unwrapped with it by
# inference (`neuv unwrap --model`), and by per-shape training (`neuv unwrap`)
# for comparison. Both with the vertex refinement off (--refine 0: the
# networks' map itself, plus repairs) and with the defaults (refinement on).
# Usage: bench/bench_category.sh BUILD_DIR [OUT_DIR] [extra neuv train options]
set -eu
B="$1"; OUT="${2:-/tmp/bench_category}"; NEUV="$B/neuv"
shift; [ $# -gt 0 ] && shift
mkdir -p "$OUT"
for i in $(seq 0 24); do "$NEUV" shape bent-capsule --member "$i" -o "$OUT/m$i.obj" --quiet; done
train=()
for i in $(seq 0 19); do train+=("$OUT/m$i.obj"); done
"$NEUV" train -o "$OUT/capsules.neuv" "${train[@]}" --report "$OUT/train.json" --quiet "$@"
for i in $(seq 20 24); do
  for r in 0 default; do
    ropt=(); [ "$r" = 0 ] && ropt=(--refine 0)
    "$NEUV" unwrap "$OUT/m$i.obj" --model "$OUT/capsules.neuv" "${ropt[@]}" -o "$OUT/cat-$r-$i.obj" \
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
print("| member | faces | refine | charts cat/own | qce_mean category | qce_mean per-shape | ratio | network charts | repairs | flipped | overlap | s category / per-shape |")
print("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
ratios = {"0": [], "default": []}
for r in ("0", "default"):
    for i in range(20, 25):
        c = json.load(open(f"{out}/cat-{r}-{i}.json")); o = json.load(open(f"{out}/own-{r}-{i}.json"))
        q, qo = c["metrics"]["qce_mean"], o["metrics"]["qce_mean"]
        ratios[r].append(q / qo)
        print(f"| {i} | {c['faces']} | {r} | {c['charts']}/{o['charts']} | {q:.4f} | {qo:.4f} | {q/qo:.3f} | "
              f"{c['model']['network_charts']}/{c['charts']} | {len(c['repairs'])} | {c['metrics']['flipped']} | "
              f"{c['metrics']['overlap_fraction']:.2g} | {c['seconds']['total']:.1f} / {o['seconds']['total']:.1f} |")
for r in ratios:
    print(f"refine {r}: category / per-shape qce_mean: worst {max(ratios[r]):.3f}, mean {statistics.mean(ratios[r]):.3f}")
PY
