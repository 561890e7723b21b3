#!/bin/sh
# Every public header compiles alone as C11 and as C++17 with -Wall -Wextra -pedantic -Werror,
# with and without WRINKLE_IMPLEMENTATION. Prints one line per failure and a summary.
CC=${CC:-cc}; CXX=${CXX:-c++}
inc="-Iinclude -I/usr/include/suitesparse"
pass=0; fail=0
for h in include/wrinkle/*.h; do
  name=$(basename "$h")
  for lang in c c++; do
    if [ "$lang" = c ]; then cc=$CC; std=-std=c11; else cc=$CXX; std=-std=c++17; fi
    for impl in "" "-DWRINKLE_IMPLEMENTATION"; do
      if printf '#include "wrinkle/%s"\nint wr_header_probe;\n' "$name" |
         "$cc" -x "$lang" $std -Wall -Wextra -pedantic -Werror $impl $inc -fsyntax-only - 2>/tmp/wr_hdr_err.$$; then
        pass=$((pass + 1))
      else
        fail=$((fail + 1)); echo "header check FAILED: $name as $lang ${impl:-(declarations)}"; head -n 5 /tmp/wr_hdr_err.$$
      fi
    done
  done
done
rm -f /tmp/wr_hdr_err.$$
echo "header checks: $pass passed, $fail failed"
[ "$fail" = 0 ]
