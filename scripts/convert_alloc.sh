#!/usr/bin/env bash
# Routes the library's allocations through core/mem.h, so that the
# application's allocator (neuv_set_allocator) and the failing allocator of
# tests/test_alloc_failure.c see every one of them.
#
#   scripts/convert_alloc.sh            convert every library source under src/
#   scripts/convert_alloc.sh FILE...    convert just these files
#
# malloc( calloc( realloc( free( strdup( become mem_alloc( mem_calloc(
# mem_realloc( mem_free( mem_strdup( (not after . or ->, so struct members
# named free stay; only with no space before the parenthesis, so prose such
# as "fold-free (check it)" stays), and "core/mem.h" is included in its
# sorted place among the project includes of .c files (a header that only
# mentions them in a comment needs no include). Re-running it is harmless:
# converted calls no longer match.
# src/cli is skipped (the CLI is a program, not the library) and so is
# src/core/mem.c (the one place that calls the C library).
#
# What it cannot decide, it lists at the end for a person to audit: memory
# that another library or the C library hands out (getline, open_memstream,
# aligned_alloc, ...) must be released with that library's own function,
# never mem_free.
set -euo pipefail
cd "$(dirname "$0")/.."

if [ $# -gt 0 ]; then
    files=("$@")
else
    mapfile -t files < <(find src -path src/cli -prune -o \( -name '*.c' -o -name '*.h' \) -print | sort)
fi

changed=0
for f in "${files[@]}"; do
    case "$f" in src/cli/* | ./src/cli/* | src/core/mem.c | ./src/core/mem.c) continue ;; esac
    perl -0777 -i -pe '
        my $n = 0;
        $n += s/(?<![\w.>-])malloc(\()/mem_alloc$1/g;
        $n += s/(?<![\w.>-])calloc(\()/mem_calloc$1/g;
        $n += s/(?<![\w.>-])realloc(\()/mem_realloc$1/g;
        $n += s/(?<![\w.>-])free(\()/mem_free$1/g;
        $n += s/(?<![\w.>-])strdup(\()/mem_strdup$1/g;
        if (/\bmem_(alloc|calloc|realloc|free|strdup)\s*\(/ && !/^#include "core\/mem\.h"/m
            && $ARGV =~ /\.c$/) {
            my @lines = split /\n/, $_, -1;
            my ($first_sys) = grep { $lines[$_] =~ /^#include </ } 0 .. $#lines;
            my @proj = grep { $lines[$_] =~ /^#include "/ } 0 .. $#lines;
            # The file'"'"'s own header comes first, above the system includes; skip it.
            @proj = grep { !defined $first_sys || $_ > $first_sys } @proj;
            my $at;
            for my $i (@proj) {
                my ($p) = $lines[$i] =~ /^#include "([^"]+)"/;
                if ($p gt "core/mem.h") { $at = $i; last; }
            }
            if (!defined $at && @proj) { $at = $proj[-1] + 1; }
            if (defined $at) {
                splice @lines, $at, 0, "#include \"core/mem.h\"";
            } else {
                my ($last) = reverse grep { $lines[$_] =~ /^#include / } 0 .. $#lines;
                $last = -1 unless defined $last;
                splice @lines, $last + 1, 0, "", "#include \"core/mem.h\"";
            }
            $_ = join "\n", @lines;
        }
    ' "$f"
    if ! git diff --quiet -- "$f" 2>/dev/null; then changed=$((changed + 1)); fi
done
echo "convert_alloc: $changed file(s) differ from the last commit" >&2

# Left for a person: allocations by the C library or another library, which
# must be released with their own function, and calls written with a space
# before the parenthesis, which the conversion leaves alone.
grep -nE '\b(aligned_alloc|posix_memalign|getline|getdelim|open_memstream|v?asprintf|realpath|strndup|scandir|tempnam|get_current_dir_name)\s*\(|(^|[^[:alnum:]_.>-])(malloc|calloc|realloc|free|strdup)\s+\(' \
    "${files[@]}" 2>/dev/null | grep -vE '^(\./)?src/(cli/|core/mem\.c)' | sed 's/^/audit: /' >&2 || true
