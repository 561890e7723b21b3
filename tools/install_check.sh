#!/bin/sh
# `make install-check`: install into a scratch DESTDIR with PREFIX=/usr, then build the drop-in
# examples (examples/minimal_c, examples/minimal_cpp) against the INSTALLED headers only, with the
# flags from the installed wrinkle.pc, and run them. The source tree's include/ is not on the path.
# pkg-config finds the .pc through PKG_CONFIG_PATH and is told where the install really is with
# --define-variable=prefix (PKG_CONFIG_SYSROOT_DIR would also rewrite the absolute
# -I/usr/include/suitesparse of the system CHOLMOD headers, which are not inside DESTDIR).
cd "$(dirname "$0")/.." || exit 2
set -e
CC=${CC:-cc}; CXX=${CXX:-c++}
dest=$(mktemp -d)
trap 'rm -rf "$dest"' EXIT
make --no-print-directory install DESTDIR="$dest" PREFIX=/usr >"$dest.log" 2>&1 || { cat "$dest.log"; rm -f "$dest.log"; exit 1; }
rm -f "$dest.log"
pc=$dest/usr/lib/pkgconfig/wrinkle.pc
[ -f "$pc" ] || { echo "install-check: $pc not installed" >&2; exit 1; }
for h in include/wrinkle/*.h; do
    cmp -s "$h" "$dest/usr/include/wrinkle/$(basename "$h")" || { echo "install-check: $h not installed" >&2; exit 1; }
done
export PKG_CONFIG_PATH="$dest/usr/lib/pkgconfig"
pkgc="pkg-config --define-variable=prefix=$dest/usr"
cflags=$($pkgc --cflags wrinkle); libs=$($pkgc --libs wrinkle)
echo "install-check: pkg-config --cflags --libs wrinkle -> $cflags $libs"
case "$cflags" in *"$dest/usr/include"*) ;; *) echo "install-check: Cflags do not point into the install" >&2; exit 1;; esac
[ "$(pkg-config --variable=prefix wrinkle)" = /usr ] || { echo "install-check: prefix is not /usr" >&2; exit 1; }
w="-Wall -Wextra -pedantic -Werror"
# shellcheck disable=SC2086
$CC -std=c11 $w -O2 examples/minimal_c/main.c $cflags $libs -o "$dest/minimal_c"
# shellcheck disable=SC2086
$CXX -std=c++17 $w -O2 examples/minimal_cpp/impl.cpp examples/minimal_cpp/main.cpp $cflags $libs -o "$dest/minimal_cpp"
echo "== minimal_c (installed headers)"; "$dest/minimal_c"
echo "== minimal_cpp (installed headers, two translation units)"; "$dest/minimal_cpp"
for d in bin/wrinkle-*; do
    [ -x "$dest/usr/bin/$(basename "$d")" ] || { echo "install-check: $d not installed" >&2; exit 1; }
done
echo "install-check: ok"
