#!/bin/sh
# CLI contract of `shlab project` (docs/CONVENTIONS.md "Output").  Truths: closed
# forms (√π/2, √(π/3), √π(1−cos t), V√(4π)), the exactness of quad on a
# constant, and a reconstruct → project round trip of chosen coefficients.
. tests/cli/lib.inc

# column of the coefficient in csv output: after the scalar context columns
coef() { awk -F, -v r="$2" 'NR == r + 1 { print $NF }' "$1"; }
field() { awk -F, -v r="$2" -v c="$3" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == c) k = i } NR == r + 1 { print $k }' "$1"; }

expect_success "project --help" project --help

# ---- errors: exit 2, one line, empty stdout
expect_usage_error "bad light spec" project --order 4 --light bogus
expect_usage_error "cap angle out of range" project --order 4 --light cap:4
expect_usage_error "cap NaN" project --order 4 --light cap:nan
expect_usage_error "lobe negative exponent" project --order 4 --light lobe:-1
expect_usage_error "sun below horizon" project --order 4 --light cie-clear:2,0
expect_usage_error "sun needs two numbers" project --order 4 --light cie-clear:1
expect_usage_error "bad method" project --order 4 --light green --method simpson
expect_usage_error "order 0" project --order 0 --light green
expect_usage_error "order not a number" project --order four --light green
expect_usage_error "NaN samples" project --order 4 --light green --method mc --samples nan
expect_usage_error "zero samples" project --order 4 --light green --method mc --samples 0
expect_usage_error "huge quad samples" project --order 4 --light green --method quad --samples 99999999
expect_usage_error "negative seed" project --order 4 --light green --method mc --seed -1
expect_usage_error "unknown option" project --order 4 --light green --bogus
expect_usage_error "missing value" project --order 4 --light
expect_usage_error "no order" project --light green
expect_usage_error "no light or exr" project --order 4
expect_usage_error "light and exr" project --order 4 --light green --exr x.exr
expect_usage_error "missing exr file" project --order 4 --exr "$TMP/nonexistent.exr"
expect_usage_error "not an exr file" project --order 4 --exr tests/cli/lib.inc
expect_usage_error "layout with light" project --order 4 --light green --layout probe
expect_usage_error "method with exr" project --order 4 --exr x.exr --method mc
expect_usage_error "samples with a closed form" project --order 4 --light cap:1 --samples 100
expect_usage_error "bad layout" project --order 4 --exr x.exr --layout cube
expect_usage_error "bad format" project --order 4 --light green --format xml
expect_usage_error "stray argument" project --order 4 --light green extra

# ---- closed forms
expect_success "lobe:1 closed form" project --order 3 --light lobe:1 --format csv
if [ "$(field "$TMP/out" 1 method)" = closed-form ] && [ "$(field "$TMP/out" 1 samples)" = 0 ] &&
   close "$(coef "$TMP/out" 1)" 0.88622692545275801 1e-15 && close "$(coef "$TMP/out" 3)" 1.0233267079464885 1e-15 &&
   close "$(coef "$TMP/out" 4)" 0 1e-15; then ok "lobe:1 = sqrt(pi)/2, sqrt(pi/3), m!=0 zero"; else notok "lobe:1: $(cat "$TMP/out")"; fi
expect_success "cap:90 degrees" project --order 2 --light cap:90 --degrees --format csv
# √π (1 − cos 90°) = √π
if close "$(coef "$TMP/out" 1)" 1.7724538509055160 1e-15; then ok "cap 90 deg c0 = sqrt(pi)"; else notok "cap: $(cat "$TMP/out")"; fi
expect_success "const:2 by quad" project --order 2 --light const:2 --method quad --samples 5 --format csv
if close "$(coef "$TMP/out" 1)" 7.0898154036220641 1e-14 && close "$(coef "$TMP/out" 3)" 0 1e-14 &&
   [ "$(field "$TMP/out" 1 samples)" = 5 ]; then ok "quad integrates a constant exactly"; else notok "const quad: $(cat "$TMP/out")"; fi

# ---- rules
expect_success "green default" project --order 4 --light green --format json
if grep -q '"method": *"quad"' "$TMP/out" && grep -q '"convention": *"cs"' "$TMP/out"; then ok "green defaults to quad, cs"; else notok "green json: $(cat "$TMP/out")"; fi
expect_success "green mc" project --order 2 --light green --method mc --samples 1000 --seed 3 --format csv
if [ "$(field "$TMP/out" 1 samples)" = 1024 ] && [ "$(field "$TMP/out" 1 seed)" = 3 ]; then ok "mc rounds samples to round(sqrt(S))^2"; else notok "mc samples: $(cat "$TMP/out")"; fi
cp "$TMP/out" "$TMP/mc1"
"$SHLAB" project --order 2 --light green --method mc --samples 1000 --seed 3 --format csv >"$TMP/mc2" 2>/dev/null
"$SHLAB" project --order 2 --light green --method mc --samples 1000 --seed 4 --format csv >"$TMP/mc3" 2>/dev/null
if cmp -s "$TMP/mc1" "$TMP/mc2" && [ "$(coef "$TMP/mc1" 1)" != "$(coef "$TMP/mc3" 1)" ]; then ok "same seed same answer, other seed differs"; else notok "mc reproducibility"; fi
expect_success "green nocs" project --order 2 --light green --convention nocs --format csv
cp "$TMP/out" "$TMP/nocs"
"$SHLAB" project --order 2 --light green --format csv >"$TMP/cs" 2>/dev/null
if close "$(coef "$TMP/nocs" 4)" "$(awk "BEGIN { printf \"%.17g\", -($(coef "$TMP/cs" 4)) }")" 1e-15 &&
   close "$(coef "$TMP/nocs" 3)" "$(coef "$TMP/cs" 3)" 1e-15; then ok "nocs flips odd m only"; else notok "nocs"; fi
for m in random qmc; do
    expect_success "green $m" project --order 2 --light cie-overcast --method $m --samples 2000
done

# ---- EXR: reconstruct chosen coefficients, project them back
if "$SHLAB" reconstruct --order 3 --coeffs 1,0.2,-0.3,0.1,0,0.05,0.4,0,-0.1 --width 512 --out "$TMP/rt.exr" >/dev/null 2>&1; then
    expect_success "project exr" project --order 3 --exr "$TMP/rt.exr" --format csv
    good=1; r=1
    for want in 1 0.2 -0.3 0.1 0 0.05 0.4 0 -0.1; do
        close "$(coef "$TMP/out" $r)" "$want" 1e-3 || good=0
        r=$((r + 1))
    done
    if [ $good = 1 ] && [ "$(field "$TMP/out" 1 width)" = 512 ] && [ "$(field "$TMP/out" 1 layout)" = latlong ]; then
        ok "exr round trip recovers the coefficients (1e-3)"; else notok "exr round trip: $(cat "$TMP/out")"; fi
    expect_usage_error "exr probe layout needs a square image" project --order 3 --exr "$TMP/rt.exr" --layout probe
    size=$(wc -c < "$TMP/rt.exr")
    head -c $((size / 2)) "$TMP/rt.exr" > "$TMP/half.exr"
    expect_usage_error "truncated exr" project --order 3 --exr "$TMP/half.exr"
    : > "$TMP/empty.exr"
    expect_usage_error "empty exr" project --order 3 --exr "$TMP/empty.exr"
else
    notok "shlab reconstruct could not write an EXR for the round trip"
fi
