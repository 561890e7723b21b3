#!/bin/sh
# `make install-check`: install into a scratch DESTDIR with PREFIX=/usr, then build the drop-in
# examples (examples/minimal_c, examples/minimal_cpp) against the INSTALLED headers only, with the
# flags from the installed wrinkle.pc, and run them; build the README's quick-start C example
# exactly as the README writes it (its code block and its command, with wrinkle-core.pc: libm only,
# no FFTW/CHOLMOD/libpng on the link line); and load a pattern file through the installed format
# readers (wrinkle-formats.pc: <wrinkle/formats/pattern.h>, libwrinkle-formats.a, cJSON). The source tree's include/ is not on the path.
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
# the README's quick start, verbatim: the C block after the marker and the `cc ... quickstart.c` line
awk '/<!-- quickstart.c/ { m = 1; next } m == 1 && /^```c/ { m = 2; next } m == 2 && /^```/ { exit } m == 2 { print }' \
    README.md > "$dest/quickstart.c"
cmd=$(awk '/<!-- quickstart.c/ { m = 1 } m && /^cc -std=c11 quickstart.c/ { print; exit }' README.md)
[ -s "$dest/quickstart.c" ] && [ -n "$cmd" ] || { echo "install-check: README quick-start block or command not found" >&2; exit 1; }
case "$($pkgc --libs wrinkle-core)" in *fftw*|*cholmod*|*png*) echo "install-check: wrinkle-core.pc links a backend" >&2; exit 1;; esac
echo "== README quick start: $cmd"
(cd "$dest" && sh -c "$(echo "$cmd" | sed "s|pkg-config|$pkgc|g")") ||
    { echo "install-check: the README's quick start does not build and run as written" >&2; exit 1; }
# the format readers for engines
cat > "$dest/formats.c" <<'EOF'
#define WRINKLE_IMPLEMENTATION
#include <wrinkle/wrinkle.h>
#include <wrinkle/formats/pattern.h>
#include <wrinkle/formats/scene.h>
#include <stdio.h>
int main(int argc, char **argv) {
    wr_pattern_file pf; wr_mesher_result res; wr_scene sc; wr_diag d;
    if (argc < 3 || wr_pattern_load(argv[1], &pf, &d) != WR_OK) { puts(argc < 3 ? "usage" : d.message); return 1; }
    if (wr_mesher_run(&pf.pattern, &pf.desc, &res, &d) != WR_OK) { puts(d.message); return 1; }
    printf("pattern '%s': %d vertices\n", pf.name, (int)res.mesh.nv);
    wr_mesher_free(&res); wr_pattern_file_free(&pf);
    if (wr_scene_load(&sc, argv[2], &d) != WR_OK) { puts(d.message); return 1; }
    printf("scene '%s' read\n", sc.name);
    wr_scene_free(&sc);
    return 0;
}
EOF
fc=$($pkgc --cflags wrinkle-formats); fl=$($pkgc --libs wrinkle-formats)
echo "== formats (installed readers): pkg-config --cflags --libs wrinkle-formats -> $fc $fl"
# shellcheck disable=SC2086
$CC -std=c11 $w -O2 "$dest/formats.c" $fc $fl -o "$dest/formats"
"$dest/formats" examples/demo/sheet.json examples/scenes/stretch.json
for d in bin/wrinkle-*; do
    [ -x "$dest/usr/bin/$(basename "$d")" ] || { echo "install-check: $d not installed" >&2; exit 1; }
done
echo "install-check: ok"
