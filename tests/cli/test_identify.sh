#!/bin/sh
# CLI contract of `shlab identify` and `shlab convert` with convention specs.
# The user bases are written here from Cartesian closed forms (AmbiX SN3D,
# the real SH table), not from shlab's output.
. tests/cli/lib.inc

expect_success "identify --help" identify --help
# the committed fixtures are what shlab writes
"$SHLAB" identify --print directions --format json >"$TMP/d.json" && cmp -s "$TMP/d.json" data/fixtures/basis/directions.json &&
    ok "directions.json is shlab identify --print directions" || notok "directions.json differs from --print directions"
"$SHLAB" identify --print light --format json >"$TMP/l.json" && cmp -s "$TMP/l.json" data/fixtures/basis/light.json &&
    ok "light.json is shlab identify --print light" || notok "light.json differs from --print light"

# an ambisonics (ambiX: SN3D, ACN, no phase) basis at order 3, from its closed forms
"$SHLAB" identify --print directions --format csv | awk -F, 'NR > 1 && NF >= 7 {
    x = $(NF-2); y = $(NF-1); z = $NF; s = sqrt(3)
    printf "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", 1, y, z, x, s*x*y, s*y*z, (3*z*z-1)/2, s*x*z, s/2*(x*x-y*y) }' >"$TMP/ambix.txt"
[ "$(wc -l <"$TMP/ambix.txt")" = 32 ] && ok "32 rows of ambiX values" || notok "ambiX rows: $(wc -l <"$TMP/ambix.txt")"
expect_success "identify ambiX" identify --basis "$TMP/ambix.txt" --format json
grep -q '"verdict":"identified"' "$TMP/out" && grep -q '"convention":"real,nocs,schmidt,acn,neg-sin,z-up"' "$TMP/out" &&
    grep -q 'real,nocs,sn3d,acn,neg-sin,z-up' "$TMP/out" && ok "ambiX named (schmidt = sn3d, acn, nocs)" || notok "ambiX: $(cat "$TMP/out")"
# order 2 only (first 4 columns): ACN and m-descending-with-a-mirror agree: ambiguous, exit 1, needs band 2
cut -d' ' -f1-4 "$TMP/ambix.txt" >"$TMP/ambix2.txt"
"$SHLAB" identify --basis "$TMP/ambix2.txt" --format json >"$TMP/out" 2>"$TMP/err"; rc=$?
[ "$rc" = 1 ] && grep -q '"verdict":"ambiguous"' "$TMP/out" && grep -q '"needs":"band 2 (order 3)' "$TMP/out" &&
    ok "order 2: ambiguous, needs band 2 (exit 1)" || notok "order 2: exit $rc $(cat "$TMP/out")"
# a sign error in band 2: no fit, exit 1, the nearest fits through order 2
awk '{ $7 = -$7; print }' "$TMP/ambix.txt" >"$TMP/bad.txt"
"$SHLAB" identify --basis "$TMP/bad.txt" --format json >"$TMP/out" 2>"$TMP/err"; rc=$?
[ "$rc" = 1 ] && grep -q '"verdict":"none"' "$TMP/out" && grep -q '"fits_through_order":2' "$TMP/out" &&
    ok "sign error: no fit, nearest fits through order 2" || notok "sign error: exit $rc $(cat "$TMP/out")"

# the light's projection (order 3) in a y-up orthonormal nocs basis: y-up means the
# formulas take (x, y, z)_shlab = (u_x, -u_z, u_y); p-functions ∝ +y_s, +z_s, +x_s
# coeffs JSON array of a result in $TMP/out, one number a line
coeffs() { sed 's/.*"coeffs":\[\([^]]*\)\].*/\1/' "$1" | tr ',' '\n'; }
"$SHLAB" identify --print light --format csv | awk -F, 'NR > 1 && NF == 11 {
    ux = $8; uy = $9; uz = $10; w = $11; x = ux; y = -uz; z = uy; k = sqrt(3/(4*atan2(0,-1)))
    pi = atan2(0, -1); h = 0.5 * sqrt(15 / pi); q = 0.25 * sqrt(5 / pi)
    c0 += w * 0.5 / sqrt(pi); c1 += w*k*y; c2 += w*k*z; c3 += w*k*x
    c4 += w*h*x*y; c5 += w*h*y*z; c6 += w*q*(3*z*z-1); c7 += w*h*x*z; c8 += w*h/2*(x*x-y*y) }
    END { printf "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", c0, c1, c2, c3, c4, c5, c6, c7, c8 }' >"$TMP/proj.txt"
expect_success "identify from a projection" identify --projection "$TMP/proj.txt" --format json
grep -q '"convention":"real,nocs,ortho,acn,neg-sin,y-up"' "$TMP/out" && ok "projection: y-up nocs named" || notok "projection: $(cat "$TMP/out")"
# the convert command it prints gives shlab's reference coefficients
expect_success "convert y-up to cs" convert --from real,nocs,y-up --to cs --in "$TMP/proj.txt" --format json
coeffs "$TMP/out" >"$TMP/got"
"$SHLAB" identify --print light --order 3 --format json >"$TMP/l2.json"
coeffs "$TMP/l2.json" >"$TMP/want"
if [ "$(wc -l <"$TMP/want")" = 9 ] && paste "$TMP/got" "$TMP/want" | awk '{ d = $1 - $2; if (d < 0) d = -d; if (!(d <= 1e-14)) bad = 1 } END { exit bad }'; then
    ok "convert of the user's light = shlab's reference"; else notok "convert: got $(cat "$TMP/got") want $(cat "$TMP/want")"; fi
# round trip through a complex layout and back
expect_success "convert to healpix" convert --from cs --to healpix --coeffs 1,2,3,4,5,6,7,8,9 --format json
expect_success "convert from healpix" convert --from healpix --to cs --coeffs "$(coeffs "$TMP/out" | paste -sd,)" --format json
[ "$(coeffs "$TMP/out" | awk '{ printf "%.12g ", $1 }')" = "1 2 3 4 5 6 7 8 9 " ] && ok "cs -> healpix -> cs" || notok "healpix round trip: $(cat "$TMP/out")"

# bad input: one line, exit 2
echo "1 2 3" >"$TMP/three.txt"
expect_refused "wrong number of values" "not a whole row" identify --basis "$TMP/three.txt"
awk '{ $1 = "nan"; print }' "$TMP/ambix.txt" >"$TMP/nan.txt"
expect_usage_error "non-finite value" identify --basis "$TMP/nan.txt"
expect_refused "nine values per row read at order 2" "order 2 needs 4" identify --basis "$TMP/bad.txt" --order 2
expect_usage_error "both inputs" identify --basis "$TMP/ambix.txt" --projection "$TMP/proj.txt"
expect_usage_error "no input" identify
expect_usage_error "order 17" identify --basis "$TMP/ambix.txt" --order 17
expect_usage_error "--print bogus" identify --print bogus
expect_refused "convert FuMa above order 4" "FuMa" convert --from fuma --to cs --coeffs 1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0
expect_refused "convert bad spec" "unknown convention token" convert --from real,foo --to cs --coeffs 1
expect_refused "convert complex count" "not a whole order" convert --from complex --to cs --coeffs 1,2,3

# --rotated: a kernel's outputs on the golden rotation cases, its conventions
# named from verify's diagnosis; the truths are the simulated kernels (the
# exact rotation with the mistake applied) and the example plug-in's nocs kernel
RFX=data/fixtures/rotation/orders_1_10.json
for sw in none:cs:shlab convention:nocs:shlab mdesc:cs,mdesc:shlab inverse:cs:inverse swap:cs:other.order \
          deg2rad:cs:degrees float:cs:float; do
    sim=${sw%%:*}; rest=${sw#*:}; want_conv=${rest%%:*}; want_rot=${rest#*:}
    if [ "$sim" = none ]; then
        "$SHLAB" verify --quiet --fixture $RFX --method wigner --convention cs --emit-candidate "$TMP/rot.json" >/dev/null 2>&1
    else
        "$SHLAB" verify --quiet --fixture $RFX --method wigner --convention cs --emit-candidate "$TMP/rot.json" --simulate "$sim" >/dev/null 2>&1
    fi
    "$SHLAB" identify --rotated "$TMP/rot.json" --format json >"$TMP/id.json" 2>"$TMP/err"; rc=$?
    conv=$(sed -n 's/.*"convention":"\([^"]*\)".*/\1/p' "$TMP/id.json"); rot=$(sed -n 's/.*"rotation":"\([^"]*\)".*/\1/p' "$TMP/id.json")
    if [ "$rc" = 0 ] && [ "$conv" = "$want_conv" ] && printf '%s' "$rot" | grep -q "$want_rot"; then
        ok "identify --rotated, simulated $sim: convention $conv, rotation '$rot'"
    else notok "identify --rotated $sim: exit $rc, convention '$conv' (want $want_conv), rotation '$rot' (want $want_rot) $(cat "$TMP/err")"; fi
done
# the to_shlab command it prints maps an m-descending vector to shlab's
"$SHLAB" verify --quiet --fixture $RFX --method wigner --convention cs --emit-candidate "$TMP/rot.json" --simulate mdesc >/dev/null 2>&1
cmd=$("$SHLAB" identify --rotated "$TMP/rot.json" --format json | sed -n 's/.*"to_shlab":"\([^"]*\)".*/\1/p' | sed 's/ --in FILE//')
out=$("$SHLAB" ${cmd#shlab } --coeffs 1,2,3,4 --format json | sed -n 's/.*"coeffs":\(\[[^]]*\]\).*/\1/p')
case "$out" in '[1.0,4.0,3.0,2.0]') ok "its convert command reverses each band: $out" ;; *) notok "convert from mdesc: '$cmd' gave $out" ;; esac
# mixed conventions are refused; a file with none of the cases too
"$SHLAB" verify --quiet --fixture $RFX --method wigner --emit-candidate "$TMP/both.json" >/dev/null 2>&1
expect_refused "identify --rotated, both conventions" 'both conventions' identify --rotated "$TMP/both.json"
printf '{"results":{"nope":[1]}}' >"$TMP/none.json"
expect_refused "identify --rotated, no case of the fixture" 'none of the cases' identify --rotated "$TMP/none.json"
expect_refused "identify --fixture without --rotated" 'only to --rotated' identify --basis "$TMP/none.json" --fixture $RFX
