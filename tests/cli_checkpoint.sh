#!/usr/bin/env bash
# neuv inspect on checkpoints: valid files print their tensors (text and JSON);
# every malformed file exits 2 with exactly one stderr line naming the file.
# Fixtures: the checked-in fuzz corpus (tests/fuzz/corpus), plus files cut and
# damaged here. Usage: cli_checkpoint.sh /path/to/neuv
set -u
NEUV=${1:?usage: cli_checkpoint.sh /path/to/neuv}
CORPUS=$(cd "$(dirname "$0")" && pwd)/fuzz/corpus
D=${NEUV_TEST_TMP:-/tmp}/cli_checkpoint
rm -rf "$D"
mkdir -p "$D"
pass=0
fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# ---- valid checkpoints ------------------------------------------------------
out=$("$NEUV" inspect "$CORPUS/valid_mlp" 2>"$D/err")
rc=$?
[ $rc -eq 0 ] && ok || bad "valid_mlp: exit $rc"
[ ! -s "$D/err" ] && ok || bad "valid_mlp: stderr not empty: $(cat "$D/err")"
echo "$out" | grep -q "version 1, 4 tensors, 13 parameters" && ok || bad "valid_mlp summary: $out"
echo "$out" | grep -Eq "mlp\.0\.w +2x3" && ok || bad "valid_mlp: mlp.0.w 2x3 missing: $out"
echo "$out" | grep -q '"model":"mlp"' && ok || bad "valid_mlp: config missing: $out"

json=$("$NEUV" inspect "$CORPUS/valid_mlp" --json)
[ $? -eq 0 ] && ok || bad "--json exit"
if command -v python3 >/dev/null; then
    echo "$json" | python3 -c '
import json, sys
d = json.load(sys.stdin)
assert d["version"] == 1 and d["parameters"] == 13, d
assert [t["name"] for t in d["tensors"]] == ["mlp.0.w", "mlp.0.b", "mlp.1.w", "mlp.1.b"], d
assert d["tensors"][2]["rows"] == 3 and d["tensors"][2]["cols"] == 1 and d["tensors"][2]["max"] == 3, d
assert json.loads(d["config"])["depth"] == 2, d
' && ok || bad "--json content: $json"
else
    echo "$json" | grep -q '"parameters":13' && ok || bad "--json content: $json"
fi
"$NEUV" inspect "$CORPUS/valid_empty" | grep -q "0 tensors, 0 parameters" && ok || bad "valid_empty"

# ---- malformed checkpoints: exit 2, one line `neuv: error: FILE: ...` ---------
GOOD="$CORPUS/valid_mlp"
size=$(wc -c < "$GOOD")
head -c $((size - 3)) "$GOOD" > "$D/truncated.neuv"
head -c $((size - 6)) "$GOOD" > "$D/truncated2.neuv"
head -c 10 "$GOOD" > "$D/short.neuv"
: > "$D/empty.neuv"
cp "$GOOD" "$D/crc.neuv"
printf '\x55' | dd of="$D/crc.neuv" bs=1 seek=$((size - 2)) conv=notrunc 2>/dev/null
cp "$GOOD" "$D/version.neuv"
printf '\x07' | dd of="$D/version.neuv" bs=1 seek=8 conv=notrunc 2>/dev/null
{ cat "$GOOD"; printf 'x'; } > "$D/trailing.neuv"
printf 'v 0 0 0\n' > "$D/mesh.obj"
mkdir -p "$D/folder.neuv"

check() { # FILE EXPECTED_MESSAGE_FRAGMENT
    "$NEUV" inspect "$1" >"$D/out" 2>"$D/err"
    local rc=$? lines
    lines=$(wc -l < "$D/err")
    [ $rc -eq 2 ] && ok || bad "$1: exit $rc (expected 2)"
    [ "$lines" -eq 1 ] && ok || bad "$1: $lines stderr lines: $(cat "$D/err")"
    grep -q "^neuv: error: $1: " "$D/err" && ok || bad "$1: error line does not name the file: $(cat "$D/err")"
    grep -q -- "$2" "$D/err" && ok || bad "$1: expected '$2' in: $(cat "$D/err")"
    [ ! -s "$D/out" ] && ok || bad "$1: wrote to stdout"
}
check "$D/truncated.neuv" "truncated checkpoint: tensor 'mlp.1.b' needs 4 bytes, 1 left"
check "$D/truncated2.neuv" "truncated checkpoint: tensor 'mlp.1.b' shape and CRC need 12 bytes, 10 left"
check "$D/short.neuv" "truncated checkpoint"
check "$D/empty.neuv" "truncated checkpoint"
check "$D/crc.neuv" "CRC mismatch in tensor 'mlp.1.b'"
check "$D/version.neuv" "wrong checkpoint version 7 (this neuv reads 1)"
check "$D/trailing.neuv" "1 unexpected bytes after the last tensor"
check "$D/mesh.obj" "bad magic"
check "$D/missing.neuv" "cannot open"
check "$D/folder.neuv" "cannot"
for f in wrong_version truncated_tensor trailing bad_magic duplicate; do
    check "$CORPUS/$f" ""
done

# Usage errors.
"$NEUV" inspect >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "no argument: expected exit 2"
"$NEUV" inspect "$GOOD" --bogus >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "unknown option: expected exit 2"

echo "cli_checkpoint: $pass passed, $fail failed"
[ $fail -eq 0 ]
