#!/usr/bin/env bash
# The command line is a program over the public API: every file of src/cli
# includes only neuv/... (the public header), its own cli/... files and
# system headers <...>, and no <...> that names one of the library's own
# folders (<mesh/mesh.h> would reach the internals through -I src just as
# well). Lists each include that breaks this and fails.
# usage: cli_public_only.sh [/path/to/neuv]   (the binary is not needed)
set -u
HERE=$(cd "$(dirname "$0")" && pwd)
SRC=$HERE/../src
if [ ! -d "$SRC/cli" ]; then echo "FAIL: no $SRC/cli"; exit 1; fi

# The library's folders: src/*/ but cli.
internal=$(cd "$SRC" && for d in */; do d=${d%/}; [ "$d" != cli ] && printf '%s\n' "$d"; done)

bad=0 files=0
while IFS= read -r file; do
    files=$((files + 1))
    while IFS= read -r hit; do
        line=${hit%%:*}
        text=${hit#*:}
        target=$(printf '%s\n' "$text" | sed -nE 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*(["<][^">]*[">]).*/\1/p')
        ok=0
        case "$target" in
            \"neuv/*\" | \"cli/*\") ok=1 ;;
            \<*\>)
                ok=1
                first=${target#<}; first=${first%%/*}
                case "$target" in */*) printf '%s\n' "$internal" | grep -qxF "$first" && ok=0 ;; esac ;;
        esac
        if [ "$ok" -eq 0 ]; then
            echo "src/cli/${file#"$SRC/cli/"}:$line: $(printf '%s' "$text" | sed -E 's/^[[:space:]]+//')"
            bad=$((bad + 1))
        fi
    done < <(grep -nE '^[[:space:]]*#[[:space:]]*include' "$file")
done < <(find "$SRC/cli" -type f \( -name '*.c' -o -name '*.h' \) | sort)

if [ "$bad" -gt 0 ]; then
    echo "cli_public_only: $bad include(s) in src/cli beyond neuv/..., cli/... and system headers"
    exit 1
fi
echo "cli_public_only: $files files include only neuv/..., cli/... and system headers"
