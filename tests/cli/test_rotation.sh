#!/bin/sh
# CLI contract of rotmat, rotate and euler, with closed-form truths.
. tests/cli/lib.inc
# coefficient I of a long-format CSV result (one row per coefficient, value last)
coef() { awk -F, -v i="$2" 'NR == i + 2 { print $NF }' "$1"; }

for c in rotmat rotate euler; do expect_success "$c --help" $c --help; done
expect_usage_error "rotmat no rotation" rotmat --order 3 --method wigner
expect_usage_error "rotmat two rotations" rotmat --order 3 --euler 1,2,3 --quat 1,0,0,0
expect_usage_error "rotmat euler 2 numbers" rotmat --order 3 --euler 1,2
expect_usage_error "rotmat NaN angle" rotmat --order 3 --euler 1,nan,3
expect_usage_error "rotmat bad method" rotmat --order 3 --method nope --euler 1,2,3
expect_usage_error "rotmat bad precision" rotmat --order 3 --precision half --euler 1,2,3
expect_usage_error "rotmat order too large" rotmat --order 33 --euler 1,2,3
expect_usage_error "rotmat band not below order" rotmat --order 3 --band 3 --euler 1,2,3
expect_success "rotmat order and band" rotmat --order 4 --band 2 --euler 1,2,3 --method blanco --format json
if grep -q '"band":2' "$TMP/out" && grep -q '"order":4' "$TMP/out"; then ok "rotmat --order 4 --band 2 prints band 2"; else notok "order+band: $(head -c 200 "$TMP/out")"; fi
# an exact method that has broken down says so on stderr (ivanic past l ~ 150;
# it accepts bands up to 200, where the golden fixtures show it failing)
"$SHLAB" rotmat --band 200 --method ivanic --euler 0.4,1.5707963267948966,-1.3 --format json >"$TMP/out" 2>"$TMP/err"; rc=$?
if [ "$rc" = 0 ] && grep -q "warning: method ivanic is inaccurate" "$TMP/err"; then ok "rotmat warns when ivanic breaks down"; else notok "no warning (rc $rc): $(head -c 200 "$TMP/err")"; fi
"$SHLAB" rotmat --band 250 --method blanco --euler 0.4,1.5707963267948966,-1.3 --format json >"$TMP/out" 2>"$TMP/err"
if [ ! -s "$TMP/err" ]; then ok "rotmat blanco band 250: no warning"; else notok "blanco warned: $(head -c 200 "$TMP/err")"; fi
expect_usage_error "rotmat choi band 1000 refused (memory)" rotmat --band 1000 --method choi --euler 1,2,3
expect_usage_error "rotmat band out of range" rotmat --band 1001 --euler 1,2,3
expect_usage_error "rotmat reflection" rotmat --order 2 --matrix 1,0,0,0,1,0,0,0,-1
expect_usage_error "rotmat skewed matrix" rotmat --order 2 --matrix 1,0.1,0,0,1,0,0,0,1
expect_usage_error "rotmat non-unit quaternion" rotmat --order 2 --quat 2,0,0,0
expect_usage_error "rotmat axis without angle" rotmat --order 2 --axis 1,0,0
expect_usage_error "rotmat zero axis" rotmat --order 2 --axis 0,0,0 --angle 1
expect_usage_error "rotmat z method tilted" rotmat --order 2 --method z --euler 0,0.1,0
expect_usage_error "rotate no coeffs" rotate --euler 1,2,3
expect_usage_error "rotate not square" rotate --euler 1,2,3 --coeffs 1,2,3
expect_usage_error "rotate order mismatch" rotate --euler 1,2,3 --coeffs 1,2,3,4 --order 3
expect_usage_error "rotate missing file" rotate --euler 1,2,3 --in "$TMP/none.json"
expect_usage_error "euler no rotation" euler

# y_1^0 ∝ z turned by +90° about x becomes ∝ −y, which is +y_1^{-1} with the
# CS phase (P_1^1 = −sinθ) and −y_1^{-1} without it.
for m in wigner reference; do
    expect_success "rotate $m Rx(90) cs" rotate --method $m --axis 1,0,0 --angle 90 --degrees --coeffs 0,0,1,0 --format csv
    v=$(coef "$TMP/out" 1)
    if close "$v" 1 1e-15; then ok "$m: z -> -y is +y_1^-1 in cs ($v)"; else notok "$m cs coeff $v"; fi
    expect_success "rotate $m Rx(90) nocs" rotate --method $m --axis 1,0,0 --angle 90 --degrees --coeffs 0,0,1,0 --convention nocs --format csv
    v=$(coef "$TMP/out" 1)
    if close "$v" -1 1e-15; then ok "$m: z -> -y is -y_1^-1 in nocs ($v)"; else notok "$m nocs coeff $v"; fi
done

# rotate then rotate --inverse returns the input (two channels from a file)
printf '{"channels":{"R":[1,0.5,-0.25,2,0.1,0.2,0.3,0.4,0.5],"G":[0,1,0,0,0,0,0,0,-1]}}' >"$TMP/c.json"
expect_success "rotate file" rotate --method wigner --quat 0.5,0.5,0.5,0.5 --in "$TMP/c.json" --format json
sed 's/.*"channels"/{"channels"/' "$TMP/out" >"$TMP/r.json"
expect_success "rotate back" rotate --method wigner --quat 0.5,0.5,0.5,0.5 --inverse --in "$TMP/r.json" --format csv
back=$(awk -F, 'NR > 1 { r = r " " $(NF-1); g = g " " $NF } END { print r g }' "$TMP/out")
want="1 0.5 -0.25 2 0.1 0.2 0.3 0.4 0.5 0 1 0 0 0 0 0 0 -1"
if awk -v a="$back" -v b="$want" 'BEGIN { n = split(a, x, " "); split(b, y, " "); if (n != 18) exit 1; for (i = 1; i <= n; i++) { d = x[i] - y[i]; if (d < 0) d = -d; if (d > 1e-14) exit 1 } }'; then
    ok "rotate --inverse undoes rotate"
else
    notok "round trip gave: $back"
fi

# euler: angles of Rz(0.3)Ry(1.1)Rz(-0.7) built from the formula by awk
M=$(awk 'BEGIN { a = 0.3; b = 1.1; g = -0.7; ca = cos(a); sa = sin(a); cb = cos(b); sb = sin(b); cg = cos(g); sg = sin(g);
  printf "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", ca*cb*cg-sa*sg, -ca*cb*sg-sa*cg, ca*sb, sa*cb*cg+ca*sg, -sa*cb*sg+ca*cg, sa*sb, -sb*cg, sb*sg, cb }')
expect_success "euler --matrix" euler --matrix "$M" --format csv
a=$(csv_value "$TMP/out" 1 1); b=$(csv_value "$TMP/out" 1 2); g=$(csv_value "$TMP/out" 1 3)
if close "$a" 0.3 1e-14 && close "$b" 1.1 1e-14 && close "$g" -0.7 1e-14; then ok "euler recovers (0.3, 1.1, -0.7)"; else notok "euler gave $a $b $g"; fi
expect_success "euler degenerate beta=pi" euler --axis 1,0,0 --angle 180 --degrees --format csv
b=$(csv_value "$TMP/out" 1 2)
if close "$b" 180 1e-15; then ok "euler beta = pi for a half turn about x"; else notok "beta $b"; fi

# --band of a z rotation: the (m, -m) pairs turn by m·θ
expect_success "rotmat band z" rotmat --band 3 --method z --euler 0.25,0,0 --format csv
v=$(awk -F, 'NR == 2 { print $(NF-6) }' "$TMP/out")
if close "$v" "$(awk 'BEGIN { printf "%.17g", cos(0.75) }')" 1e-15; then ok "z band 3: R[-3,-3] = cos 3θ"; else notok "R[-3,-3] = $v"; fi

# found by fuzzing: an axis 1e-150 away from z (β ≈ 1e-150) made blanco's
# single-band recurrence overflow ("non-finite value", exit 2); it must agree
# with the MPFR reference entry by entry
expect_success "rotmat blanco band 7, beta 1e-150" rotmat --band 7 --method blanco --axis 0,1e-150,1 --angle 0.5 --format csv
cut -d, -f7- "$TMP/out" >"$TMP/blanco"
"$SHLAB" rotmat --band 7 --method reference --axis 0,1e-150,1 --angle 0.5 --format csv | cut -d, -f7- >"$TMP/ref"
if [ "$(wc -l <"$TMP/ref")" = 16 ] && paste -d, "$TMP/blanco" "$TMP/ref" | awk -F, 'NR > 1 { h = NF / 2; for (i = 2; i <= h; i++) { d = $i - $(i + h); if (d < 0) d = -d; if (!(d <= 1e-13)) exit 1 } }'; then
    ok "blanco band 7 at beta 1e-150 = reference"
else notok "blanco band 7 at beta 1e-150: $(head -c 300 "$TMP/blanco")"; fi
