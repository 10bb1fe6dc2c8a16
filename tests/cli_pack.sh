#!/bin/bash
# neuv pack on a UV sample from another tool: exit 0, output and pictures
# written, efficiency printed and not below the file's own; bad usage exits 2.
NEUV="$1"
SHARED="${NEUV_SHARED:-../shared}"
TMP="${NEUV_TEST_TMP:-/tmp}/cli_pack"
mkdir -p "$TMP"
pass=0; fail=0
check() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1"; fi; }

IN="$SHARED/uv-samples/spot-xatlas.obj"
if [ ! -f "$IN" ]; then echo "SKIP: $IN absent"; exit 77; fi

"$NEUV" pack "$IN" -o "$TMP/spot-packed.obj" --preview "$TMP/spot" > "$TMP/out.txt" 2> "$TMP/err.txt"
rc=$?
cat "$TMP/out.txt"
check "pack exits 0" "[ $rc -eq 0 ]"
check "output written" "[ -s '$TMP/spot-packed.obj' ]"
check "uv picture written" "[ -s '$TMP/spot-uv.png' ]"
check "checker picture written" "[ -s '$TMP/spot-checker.png' ]"
check "positions kept" "[ \"\$(grep -c '^v ' '$IN')\" -eq \"\$(grep -c '^v ' '$TMP/spot-packed.obj')\" ]"
before=$(awk '/packing efficiency before/ {print $4}' "$TMP/out.txt")
after=$(awk '/packing efficiency after/ {print $4}' "$TMP/out.txt")
check "efficiency printed" "[ -n '$after' ]"
check "efficiency not below the file's own" "awk -v a='$after' -v b='$before' 'BEGIN { exit !(a >= b) }'"

# The packing's threads search each chart's places side by side: the same bytes on one and on two.
"$NEUV" pack "$IN" -o "$TMP/t1.obj" --threads 1 --resolution 512 > /dev/null 2>&1
"$NEUV" pack "$IN" -o "$TMP/t2.obj" --threads 2 --resolution 512 > /dev/null 2>&1
check "same bytes on 1 and 2 threads" "[ -s '$TMP/t1.obj' ] && cmp -s '$TMP/t1.obj' '$TMP/t2.obj'"
"$NEUV" pack "$IN" -o "$TMP/x.obj" --threads 0 > /dev/null 2> "$TMP/err.txt"
check "--threads 0 exits 2" "[ \$? -eq 2 ] && grep -q 'neuv: error' '$TMP/err.txt'"

"$NEUV" pack "$TMP/spot-packed.obj" -o "$TMP/again.obj" --resolution 512 --padding 4 --keep-scale > /dev/null 2>&1
check "repacking a packed file works" "[ \$? -eq 0 ] && [ -s '$TMP/again.obj' ]"
"$NEUV" pack "$IN" -o "$TMP/x.obj" --padding 9999 > /dev/null 2> "$TMP/err.txt"
check "absurd padding exits 2" "[ \$? -eq 2 ] && grep -q 'neuv: error' '$TMP/err.txt'"
"$NEUV" pack "$IN" > /dev/null 2>&1
check "missing -o exits 2" "[ \$? -eq 2 ]"
"$NEUV" pack "$SHARED/meshes/spot.obj" -o "$TMP/nouv.obj" > /dev/null 2>&1
rc=$?
grep -q '^vt' "$SHARED/meshes/spot.obj" || check "input without UVs exits 2" "[ $rc -eq 2 ]"
"$NEUV" pack "$IN" -o "$IN" > /dev/null 2>&1
check "refuses to overwrite the input" "[ \$? -eq 2 ]"

echo "cli_pack: $pass passed, $fail failed"
[ $fail -eq 0 ]
