#!/bin/sh
# Every public header's top-block EXAMPLE compiles and runs, as C11 and as C++17.
#
# The marker convention (docs/CONVENTIONS.md, "Headers"): in the leading doc comment, a line
#     * EXAMPLE            (optionally followed by a note: " * EXAMPLE (one-shot solve)")
# starts the example; its code is every following line indented four spaces past the comment's
# "* " (i.e. beginning " *     "), up to the first line that is not (a blank " *" line or prose at
# the normal two-space indent ends it). Code lines that begin with "static " are placed at file
# scope (helper callbacks); all other lines become the body of main(). `return 1;` in the example
# means failure. The example must be complete: no "..." placeholders, every name declared.
#
# Each example is wrapped as
#     #include <stdio.h> <stdlib.h> <string.h> <math.h> <stdint.h>
#     #define WRINKLE_IMPLEMENTATION
#     #include "wrinkle/<header>"
#     <static lines>
#     int main(void) { <body> return 0; }
# compiled with -Wall -Wextra -pedantic -Werror (no warning is relaxed), linked with the libraries
# the headers name (FFTW for spectrum.h, CHOLMOD with -DWR_USE_CHOLMOD=1, ARPACK with -DWR_USE_ARPACK=1), and run in a scratch
# directory (examples may write files) under a time limit of EXAMPLE_SECONDS (default 10 s; the
# examples are written to take well under 1 s). Prints one line per failure and a summary.
# wrinkle.h (the umbrella header) has no example of its own: its examples are examples/minimal_*.
CC=${CC:-cc}; CXX=${CXX:-c++}
root=$(cd "$(dirname "$0")/.." && pwd) || exit 2
limit=${EXAMPLE_SECONDS:-10}
flags="-O1 -Wall -Wextra -pedantic -Werror -ffp-contract=off -I$root/include -I/usr/include/suitesparse -DWR_USE_CHOLMOD=1 -DWR_USE_ARPACK=1"
libs="-lcholmod -larpack -lfftw3 -lm"
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
pass=0; fail=0

for h in "$root"/include/wrinkle/*.h; do
    name=$(basename "$h")
    [ "$name" = wrinkle.h ] && continue
    base=${name%.h}
    # the leading comment only: from line 1 to its first " */"
    awk 'NR == 1 && !/^\/\*/ { exit } { print } /\*\// { exit }' "$h" > "$tmp/$base.doc"
    awk '
        state == 0 && /^ \* EXAMPLE([ (].*)?$/ { state = 1; found = 1; next }
        state == 1 {
            if ($0 ~ /^ \*     /) {
                line = substr($0, 4)              # drop " * ", keep the code indentation
                if (line ~ /^ *static /) { sub(/^ */, "", line); print line > top } else print line > body
            } else exit
        }
        END { if (!found) exit 3 }
    ' top="$tmp/$base.top" body="$tmp/$base.body" "$tmp/$base.doc"
    st=$?
    if [ $st = 3 ]; then fail=$((fail + 1)); echo "example check FAILED: $name has no ' * EXAMPLE' block"; continue; fi
    if [ ! -s "$tmp/$base.body" ]; then fail=$((fail + 1)); echo "example check FAILED: $name: EXAMPLE has no code lines"; continue; fi
    if sed 's|//.*||' "$tmp/$base.body" | grep '\.\.\.' >/dev/null; then
        fail=$((fail + 1)); echo "example check FAILED: $name: the example has a '...' placeholder"; continue
    fi
    touch "$tmp/$base.top"
    {
        printf '#include <math.h>\n#include <stdint.h>\n#include <stdio.h>\n#include <stdlib.h>\n#include <string.h>\n'
        printf '#define WRINKLE_IMPLEMENTATION\n#include "wrinkle/%s"\n\n' "$name"
        cat "$tmp/$base.top"
        printf '\nint main(void) {\n'
        cat "$tmp/$base.body"
        printf '    return 0;\n}\n'
    } > "$tmp/$base.src"
    for lang in c c++; do
        if [ "$lang" = c ]; then cc=$CC; std=-std=c11; else cc=$CXX; std=-std=c++17; fi
        exe=$tmp/$base.$lang.exe
        if ! "$cc" -x "$lang" $std $flags "$tmp/$base.src" -o "$exe" $libs 2>"$tmp/err"; then
            fail=$((fail + 1)); echo "example check FAILED: $name as $lang does not compile"; head -n 8 "$tmp/err"
            continue
        fi
        mkdir -p "$tmp/run"
        if (cd "$tmp/run" && OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 timeout "$limit" "$exe") >"$tmp/out" 2>&1; then
            pass=$((pass + 1))
            [ -n "$VERBOSE" ] && { echo "== $name ($lang)"; cat "$tmp/out"; }
        else
            fail=$((fail + 1)); echo "example check FAILED: $name as $lang exited non-zero (or ran over ${limit} s)"
            head -n 5 "$tmp/out"
        fi
    done
done
echo "example checks: $pass passed, $fail failed"
[ "$fail" = 0 ]
