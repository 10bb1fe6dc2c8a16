#!/usr/bin/env bash
# The installed library as its users see it: `cmake --install` into a fresh
# prefix, then examples/unwrap.c compiled against the installed header only,
# through pkg-config (shared, and static against libneuv.a) and through
# find_package(neuv); each build runs. libneuv.so must export only neuv_*.
# usage: cli_install.sh /path/to/build/neuv   (the build folder is its folder)
set -u
NEUV=${1:?usage: cli_install.sh /path/to/build/neuv}
HERE=$(cd "$(dirname "$0")" && pwd)
SRC=$(cd "$HERE/.." && pwd)
BUILD=$(cd "$(dirname "$NEUV")" && pwd)
for tool in cmake cc pkg-config nm readelf; do
    if ! command -v "$tool" >/dev/null; then echo "SKIP: no $tool"; exit 77; fi
done
if [ ! -e "$BUILD/libneuv.so" ]; then echo "FAIL: no $BUILD/libneuv.so"; exit 1; fi
# A sanitizer build's library needs the ASan runtime loaded first, which a
# plain cc build of the example does not do.
if readelf -d "$BUILD/libneuv.so" | grep -q 'NEEDED.*libasan'; then
    echo "SKIP: $BUILD is a sanitizer build"; exit 77
fi
mkdir -p "${NEUV_TEST_TMP:-/tmp}"
TMP=$(mktemp -d "${NEUV_TEST_TMP:-/tmp}/cli_install.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
P=$TMP/prefix

passed=0 failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }

if ! cmake --install "$BUILD" --prefix "$P" >"$TMP/install.log" 2>&1; then
    cat "$TMP/install.log"; echo "FAIL: cmake --install"; exit 1
fi
for f in lib/libneuv.so lib/libneuv.a include/neuv/neuv.h bin/neuv lib/pkgconfig/neuv.pc \
         lib/cmake/neuv/neuvConfig.cmake lib/cmake/neuv/neuvConfigVersion.cmake; do
    [ -e "$P/$f" ] && ok || bad "not installed: $f"
done
if ls "$P"/lib/libneuv.so.[0-9]* >/dev/null 2>&1; then ok; else bad "no versioned libneuv.so.N"; fi
if "$P/bin/neuv" --version | grep -q '^neuv [0-9]'; then ok; else bad "installed neuv --version"; fi

# The shared library exports the public API and nothing else.
exported=$(nm -D --defined-only "$P/lib/libneuv.so" | awk '{print $NF}')
others=$(printf '%s\n' "$exported" | grep -v '^neuv_')
if [ -z "$others" ]; then ok; else bad "libneuv.so exports more than neuv_*:"$'\n'"$others"; fi
for f in neuv_version neuv_mesh_load neuv_unwrap neuv_unwrap_report_json; do
    if printf '%s\n' "$exported" | grep -qx "$f"; then ok; else bad "libneuv.so does not export $f"; fi
done

# Every path the compile or link uses lies outside the source tree (the
# temporary prefix may lie inside it, under the build folder).
inside_source() {
    local p
    for p in "$@"; do
        p=${p#-I}; p=${p#-L}
        case "$p" in "$TMP"/*) ;; "$SRC"/*) echo "$p" ;; esac
    done
}
export PKG_CONFIG_PATH=$P/lib/pkgconfig
cflags=$(pkg-config --cflags neuv) libs=$(pkg-config --libs neuv) static_libs=$(pkg-config --static --libs neuv)
if [ -n "$cflags" ] && [ -n "$libs" ]; then ok; else bad "pkg-config neuv: $(pkg-config --cflags --libs neuv 2>&1)"; fi
# shellcheck disable=SC2086
leaks=$(inside_source $cflags $libs $static_libs)
[ -z "$leaks" ] && ok || bad "pkg-config gives paths inside the source tree: $leaks"
# The headers the example includes (cc -M), but for the example itself.
# shellcheck disable=SC2086
if cc $cflags -M "$SRC/examples/unwrap.c" >"$TMP/deps" 2>"$TMP/err"; then
    # shellcheck disable=SC2046
    leaks=$(inside_source $(tr -d '\\' <"$TMP/deps" | tr ' ' '\n' | grep / | grep -v "^$SRC/examples/unwrap.c$"))
    [ -z "$leaks" ] && ok || bad "the example's compile reads inside the source tree: $leaks"
    grep -q "$P/[^ ]*include/neuv/neuv.h" "$TMP/deps" && ok || bad "neuv.h not from $P/include"
else bad "cc -M: $(cat "$TMP/err")"; fi

# check_run LABEL PROGRAM: runs the example and checks what it prints: the
# mesh, the chart count, and the report, whose charts agree and which has
# no flipped or overlapping triangles.
check_run() {
    local label=$1; shift
    if ! "$@" >"$TMP/$label.out" 2>"$TMP/$label.err"; then
        bad "$label: exit $?: $(cat "$TMP/$label.err")"; return
    fi
    local charts
    charts=$(sed -n 's/^charts: \([0-9][0-9]*\)$/\1/p' "$TMP/$label.out")
    if grep -Eq '^neuv [0-9.]+: box with [0-9]+ vertices, [0-9]+ faces$' "$TMP/$label.out" &&
       [ -n "$charts" ] && [ "$charts" -ge 1 ]; then ok
    else bad "$label: output: $(head -c 300 "$TMP/$label.out")"; return; fi
    if ! command -v python3 >/dev/null; then
        grep -q "\"charts\":$charts," "$TMP/$label.out" && ok || bad "$label: report lacks charts $charts"
        return
    fi
    if python3 - "$TMP/$label.out" "$charts" <<'EOF'
import json, sys
lines = open(sys.argv[1]).read().splitlines()
j = json.loads(next(l for l in lines if l.startswith("{")))
out = next(l for l in lines if l.startswith("output: ")).split()
# Output vertices are split along seams (more than the input's), triangles are the input's.
assert int(out[1]) > j["input_vertices"] and int(out[6]) == j["input_faces"], out
assert j["method"] == "lscm", j["method"]
assert j["charts"] == int(sys.argv[2]), j["charts"]
assert j["metrics"]["flipped"] == 0 and j["metrics"]["overlap_fraction"] == 0, j["metrics"]
EOF
    then ok; else bad "$label: report: $(head -c 300 "$TMP/$label.out")"; fi
}

# Shared, the compile line of the README.
# shellcheck disable=SC2086
if cc "$SRC/examples/unwrap.c" $cflags $libs -o "$TMP/unwrap-shared" 2>"$TMP/err"; then
    ok
    if readelf -d "$TMP/unwrap-shared" | grep -q 'NEEDED.*libneuv\.so'; then ok; else bad "shared: no libneuv.so needed"; fi
    resolved=$(LD_LIBRARY_PATH=$P/lib ldd "$TMP/unwrap-shared" | awk '/libneuv/ {print $3}')
    case "$resolved" in "$P/lib/"*) ok ;; *) bad "shared: libneuv resolves to '$resolved'" ;; esac
    check_run shared env LD_LIBRARY_PATH="$P/lib" "$TMP/unwrap-shared"
else bad "shared compile: $(cat "$TMP/err")"; fi

# Static: libneuv.a, whole, with what --static adds (so Libs.private and
# Requires.private must name every library any of its objects needs).
whole="-Wl,--whole-archive -l:libneuv.a -Wl,--no-whole-archive"
# shellcheck disable=SC2086
if cc "$SRC/examples/unwrap.c" $cflags ${static_libs/-lneuv/$whole} -o "$TMP/unwrap-static" 2>"$TMP/err"; then
    ok
    if readelf -d "$TMP/unwrap-static" | grep -q 'NEEDED.*libneuv'; then bad "static: needs libneuv.so"; else ok; fi
    check_run static "$TMP/unwrap-static"
else bad "static link: $(tail -5 "$TMP/err")"; fi

# CMake: find_package(neuv) and neuv::neuv (examples/CMakeLists.txt).
if cmake -S "$SRC/examples" -B "$TMP/cmake-build" -DCMAKE_PREFIX_PATH="$P" -DCMAKE_BUILD_TYPE=Release \
       >"$TMP/cmake.log" 2>&1 &&
   cmake --build "$TMP/cmake-build" >>"$TMP/cmake.log" 2>&1; then
    ok
    check_run cmake "$TMP/cmake-build/unwrap"
else bad "CMake consumer: $(tail -20 "$TMP/cmake.log")"; fi

echo "cli_install: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
