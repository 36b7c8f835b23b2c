#!/bin/sh
# test_install.sh — `make install` gives a library that a program compiled
# with `pkg-config --cflags --libs shlab` can use and run without
# LD_LIBRARY_PATH (shlab.pc's Libs carry an rpath), whose --cflags expose no
# dependency's include path (shlab's headers include only standard headers),
# whose static flags link, and a staged install (DESTDIR) that works once
# copied to its PREFIX.  Truth for the program's output: y_0^0 = 1/√(4π).
. "$(dirname "$0")/lib.inc"
BUILD=${BUILD:-build}
ROOT=$(pwd)
if ! command -v pkg-config >/dev/null || ! command -v make >/dev/null; then
    ok "# skip install test (no make or pkg-config)"; exit 0
fi
# the sanitizer build's library needs the sanitizer runtime in the program too
san="" sanmake="SANITIZE=0"
case "$BUILD" in *san*) san="-fsanitize=address,undefined" sanmake="SANITIZE=1" ;; esac

cat >"$TMP/prog.c" <<'EOF'
#include <shlab.h>
#include <stdio.h>
int main(void)
{
    double y[4];
    if (sh_eval(2, SH_CS, 0.5, 0.25, y) != SH_OK) { fprintf(stderr, "%s\n", sh_last_error()); return 1; }
    printf("%.17g\n", y[0]);
    return 0;
}
EOF
y00=0.28209479177387814

# install into PREFIX, compile against it with pkg-config, run without LD_LIBRARY_PATH
P=$TMP/prefix
if make -s -C "$ROOT" install BUILD="$BUILD" $sanmake PREFIX="$P" >"$TMP/log" 2>&1; then ok "make install PREFIX=$P"
else notok "make install: $(tail -5 "$TMP/log")"; fi
for f in bin/shlab lib/libshlab.so.0 lib/libshlab.a include/shlab.h include/shlab/core.h lib/pkgconfig/shlab.pc \
         share/man/man1/shlab.1 share/doc/shlab/CONVENTIONS.md; do
    [ -e "$P/$f" ] || missing="$missing $f"
done
[ -z "$missing" ] && ok "installed files present" || notok "missing:$missing"
PKG_CONFIG_PATH=$P/lib/pkgconfig; export PKG_CONFIG_PATH
cf=$(pkg-config --cflags shlab)
[ "$(echo $cf)" = "-I$P/include" ] && ok "pkg-config --cflags is only -I\$PREFIX/include" || notok "--cflags: $cf"
grep -q '#include' "$P/include/shlab/core.h" && ! grep -h '#include <' "$P/include/shlab.h" "$P"/include/shlab/*.h | grep -vq '<std' \
    && ok "installed headers include only standard headers" || notok "headers: $(grep -h '#include <' "$P"/include/shlab/*.h | sort -u | tr '\n' ' ')"
if cc -std=c11 -Wall -Wextra $san -o "$TMP/prog" "$TMP/prog.c" $(pkg-config --cflags --libs shlab) 2>"$TMP/err"; then
    out=$(env -u LD_LIBRARY_PATH "$TMP/prog" 2>&1)
    [ "$out" = "$y00" ] && ok "program linked by pkg-config runs without LD_LIBRARY_PATH" || notok "run: $out"
    ldd "$TMP/prog" | grep -q "libshlab.so.0 => $P/lib/libshlab.so.0" && ok "it loads \$PREFIX/lib/libshlab.so.0" \
        || notok "ldd: $(ldd "$TMP/prog" | grep shlab)"
else notok "compile with pkg-config: $(head -5 "$TMP/err")"; notok "(not run)"; fi
# a plug-in kernel built against the installed ABI header alone, verified by the installed shlab
if cc -std=c11 -O2 -shared -fPIC -I"$P/include" -o "$TMP/kernels.so" "$ROOT/tests/plugins/kernels.c" -lm 2>"$TMP/err" &&
   env -u LD_LIBRARY_PATH "$P/bin/shlab" verify --quiet --fixture "$ROOT/data/fixtures/rotation/orders_1_10.json" \
       --plugin "$TMP/kernels.so:rot_matrix_d" --abi matrix-d >"$TMP/out" 2>&1; then
    ok "a plug-in built with -I\$PREFIX/include (shlab/kernel.h) passes the installed verify"
else notok "plug-in against the installed header: $(head -5 "$TMP/err") $(tail -3 "$TMP/out")"; fi
# static: libshlab.a plus the Libs.private flags
if cc -std=c11 $san -o "$TMP/prog_static" "$TMP/prog.c" $(pkg-config --cflags shlab) \
        $(pkg-config --static --libs shlab | sed 's/-lshlab/-l:libshlab.a/') 2>"$TMP/err"; then
    [ "$("$TMP/prog_static")" = "$y00" ] && ! ldd "$TMP/prog_static" | grep -q shlab \
        && ok "static link with pkg-config --static --libs" || notok "static program"
else notok "static link: $(head -5 "$TMP/err")"; fi

# staged install (DESTDIR), then copied to its PREFIX as a package manager would
F=$TMP/final; D=$TMP/stage
if make -s -C "$ROOT" install BUILD="$BUILD" $sanmake DESTDIR="$D" PREFIX="$F" >"$TMP/log" 2>&1 && [ ! -e "$F" ] \
    && grep -q "^prefix=$F\$" "$D$F/lib/pkgconfig/shlab.pc"; then ok "make install DESTDIR=... stages under DESTDIR, .pc names PREFIX"
else notok "staged install: $(tail -5 "$TMP/log")"; fi
mkdir -p "$F" && cp -a "$D$F/." "$F/"
PKG_CONFIG_PATH=$F/lib/pkgconfig
if cc -std=c11 $san -o "$TMP/prog2" "$TMP/prog.c" $(pkg-config --cflags --libs shlab) 2>"$TMP/err"; then
    [ "$(env -u LD_LIBRARY_PATH "$TMP/prog2")" = "$y00" ] && ok "staged install runs once at PREFIX" || notok "staged run"
else notok "compile against the staged install: $(head -5 "$TMP/err")"; fi
