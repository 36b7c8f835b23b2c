#!/bin/sh
# The golden fixtures are reproducible: `shlab fixtures` writes exactly the
# committed bytes (zeros as 0.0, never -0.0), for the reference files and the
# Taylor-1.5 file.  The independent truth is the committed file itself, which
# the verify tests check against identities and the exact rotation.
. tests/cli/lib.inc
FX=data/fixtures/rotation
mkdir -p "$TMP/fx"
"$SHLAB" fixtures --out "$TMP/fx" --quiet --format json >/dev/null 2>"$TMP/err" && ok "fixtures regenerated" \
    || notok "fixtures: $(head -c 200 "$TMP/err")"
"$SHLAB" fixtures --out "$TMP/fx" --method taylor1.5 --quiet --format json >/dev/null 2>"$TMP/err" && ok "taylor1.5 fixtures regenerated" \
    || notok "fixtures --method taylor1.5: $(head -c 200 "$TMP/err")"
for f in orders_1_10.json bands_50_200.json orders_1_10_taylor1.5.json; do
    if cmp -s "$TMP/fx/$f" "$FX/$f"; then ok "$f: byte-identical to the committed file"
    else notok "$f differs from the committed file: $(cmp "$TMP/fx/$f" "$FX/$f" 2>&1 | head -1)"; fi
done
grep -l -- '[^0-9.e]-0\.0[],]' "$TMP"/fx/*.json >/dev/null 2>&1 && notok "a negative zero was written" || ok "no negative zero written"
