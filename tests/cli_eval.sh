#!/usr/bin/env bash
# neuv eval against the independent numpy reference (tests/reference_metrics.py)
# on every UV map of shared/uv-samples: every metric within 1e-6 relative
# (1e-12 absolute for values at zero), counts exactly. Also the CLI's errors.
# usage: cli_eval.sh /path/to/neuv
set -u
NEUV=${1:?usage: cli_eval.sh /path/to/neuv}
HERE=$(cd "$(dirname "$0")" && pwd)
SAMPLES=${NEUV_SHARED:-$HERE/../../shared}/uv-samples
TMP=${NEUV_TEST_TMP:-/tmp}/cli_eval.$$
if [ ! -d "$SAMPLES" ]; then echo "SKIP: no $SAMPLES"; exit 77; fi
PY=
for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null && "$p" -c 'import numpy' 2>/dev/null; then PY=$p; break; fi
done
if [ -z "$PY" ]; then echo "SKIP: no python3 with numpy (scripts/setup.sh installs python3-numpy)"; exit 77; fi
mkdir -p "$TMP"
trap 'rm -rf "$TMP"' EXIT

passed=0 failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }

for obj in "$SAMPLES"/*.obj; do
    name=$(basename "$obj" .obj)
    if ! "$NEUV" eval "$obj" --json >"$TMP/$name.neuv.json" 2>"$TMP/$name.err"; then
        bad "$name: neuv eval failed: $(cat "$TMP/$name.err")"; continue
    fi
    if ! "$PY" "$HERE/reference_metrics.py" "$obj" >"$TMP/$name.ref.json"; then
        bad "$name: reference failed"; continue
    fi
    if "$PY" - "$TMP/$name.neuv.json" "$TMP/$name.ref.json" "$name" <<'EOF'
import json, math, sys
ours = json.load(open(sys.argv[1]))
ref = json.load(open(sys.argv[2]))["metrics"]
name = sys.argv[3]
m = ours["metrics"]
bad = []
for key, want in ref.items():
    got = m.get(key, "missing")
    if want is None or got is None or got == "missing":
        if got != want:
            bad.append("%s: neuv %s, reference %s" % (key, got, want))
    elif isinstance(want, int) and isinstance(got, int):
        if got != want:
            bad.append("%s: neuv %d, reference %d" % (key, got, want))
    elif not abs(got - want) <= 1e-6 * max(abs(got), abs(want)) + 1e-12:
        bad.append("%s: neuv %.12g, reference %.12g (rel %.2g)" %
                   (key, got, want, abs(got - want) / max(abs(got), abs(want))))
for key in ("version", "input", "vertices", "faces"):
    if key not in ours:
        bad.append("JSON has no '%s'" % key)
if bad:
    print("%s: %s" % (name, "; ".join(bad)))
    sys.exit(1)
print("%s: %d metrics agree (charts %s, qce_mean %.6f, overlap %.3g)" %
      (name, len(ref), m["charts"], m["qce_mean"], m["overlap_fraction"]))
EOF
    then ok; else bad "$name: metrics differ from the reference"; fi
done

# The table form runs and names the metrics.
first=$(ls "$SAMPLES"/*.obj | head -n 1)
if "$NEUV" eval "$first" >"$TMP/table.txt" 2>&1 && grep -q "qce_mean" "$TMP/table.txt"; then ok
else bad "table output: $(head -c 300 "$TMP/table.txt")"; fi

# A mesh without UVs: exit 2 and the one-line message.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$TMP/nouv.obj"
"$NEUV" eval "$TMP/nouv.obj" >"$TMP/nouv.out" 2>"$TMP/nouv.err"; rc=$?
if [ $rc -eq 2 ] && grep -q "^neuv: error: .*nouv.obj: no UVs: neuv eval needs a mesh that carries texture coordinates$" "$TMP/nouv.err" \
   && [ "$(wc -l <"$TMP/nouv.err")" -eq 1 ]; then ok
else bad "no-UV mesh: exit $rc, stderr: $(cat "$TMP/nouv.err")"; fi

# Usage errors exit 2.
"$NEUV" eval "$first" --preview-color rainbow >/dev/null 2>&1; rc=$?
if [ $rc -eq 2 ]; then ok; else bad "--preview-color rainbow: exit $rc, expected 2"; fi
"$NEUV" eval >/dev/null 2>&1; rc=$?
if [ $rc -eq 2 ]; then ok; else bad "no input: exit $rc, expected 2"; fi

echo "cli_eval: $passed passed, $failed failed"
[ $failed -eq 0 ]
