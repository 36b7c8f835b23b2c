#!/bin/sh
# test_taylor.sh — shlab deriv and shlab taylor-error (CLI contract and a few
# identities that do not depend on shlab's own numbers).
. "$(dirname "$0")/lib.inc"

# deriv: J band 1 in nocs is Figure 2's [[0,0,0],[0,0,-1],[0,1,0]]
expect_success "deriv J order 2 nocs" deriv --order 2 --k 1 --convention nocs --format csv
# columns: order,k,beta,unit,convention,way,row,c0..c3
v=$(awk -F, 'NR==4 {print $11}' "$TMP/out"); w=$(awk -F, 'NR==5 {print $10}' "$TMP/out")
if close "$v" -1 1e-15 && close "$w" 1 1e-15; then ok "deriv J band 1 (nocs) = Figure 2"; else notok "deriv J band 1: $v $w"; fi
expect_success "deriv json" deriv --order 3 --k 2 --beta 30 --degrees --format json
if grep -q '"convention"' "$TMP/out" && grep -q '"k": *2,' "$TMP/out" && grep -q '"matrix"' "$TMP/out" && ! grep -qi nan "$TMP/out"; then ok "deriv json fields"; else notok "deriv json fields"; fi
# the two ways agree (k = 3, beta = 1.1, order 5)
"$SHLAB" deriv --order 5 --k 3 --beta 1.1 --format csv > "$TMP/a" 2>/dev/null
"$SHLAB" deriv --order 5 --k 3 --beta 1.1 --way generator --format csv > "$TMP/b" 2>/dev/null
d=$(paste -d, "$TMP/a" "$TMP/b" | awk -F, 'NR > 1 { h = NF / 2; for (i = 8; i <= h; i++) { x = $i - $(i + h); if (x < 0) x = -x; if (x > m) m = x } } END { print m + 0 }')
if close "$d" 0 1e-12; then ok "deriv recursion == generator (max diff $d)"; else notok "deriv ways differ by $d"; fi
# k = 40 at order 3: J has eigenvalues 0, ±i (band 1), 0, ±i, ±2i (band 2), so
# trace(J^40) = 2 + 2 + 2·2^40 = 2199023255556 (the trace of J^41 is 0)
expect_success "deriv k 40" deriv --order 3 --k 40 --format csv
t=$(awk -F, 'NR > 1 { r = $7; tr += $(8 + r) } END { printf "%.17g", tr }' "$TMP/out")
close "$t" 2199023255556 1e-12 && ok "deriv k=40: trace $t = 4 + 2^41" || notok "deriv k=40 trace $t"
# any β: β and β + 2π·1000 agree (R_Y is 2π-periodic)
b2=$(awk 'BEGIN { printf "%.17g", 0.4 + 2000 * atan2(0, -1) }')
"$SHLAB" deriv --order 4 --k 2 --beta 0.4 --format csv > "$TMP/a" 2>/dev/null
"$SHLAB" deriv --order 4 --k 2 --beta "$b2" --format csv > "$TMP/b" 2>/dev/null
d=$(paste -d, "$TMP/a" "$TMP/b" | awk -F, 'NR > 1 { h = NF / 2; for (i = 8; i <= h; i++) { x = $i - $(i + h); if (x < 0) x = -x; if (x > m) m = x } } END { print m + 0 }')
[ -s "$TMP/b" ] && close "$d" 0 1e-9 && ok "deriv beta vs beta + 2000 pi (max diff $d)" || notok "deriv large beta: diff $d"
expect_success "deriv huge beta" deriv --order 3 --k 1 --beta 1e300
expect_usage_error "deriv k overflows" deriv --order 3 --k 5000
expect_usage_error "deriv without --k" deriv --order 3
expect_usage_error "deriv bad k" deriv --order 3 --k -1
expect_usage_error "deriv bad way" deriv --order 3 --k 1 --way magic
expect_usage_error "deriv order too large" deriv --order 40 --k 1
expect_usage_error "deriv nan beta" deriv --order 3 --k 1 --beta nan

# taylor-error: zero at beta 0; Taylor 2 error ~ 8x when beta doubles (O(beta^3))
expect_success "taylor-error sweep" taylor-error --order 5 --taylor 2 --beta-max 0.02 --steps 2 --format csv
# columns: order,taylor,method,convention,lobe_exp,unit,beta,max,mean,lobe
e1=$(csv_value "$TMP/out" 2 8); e2=$(csv_value "$TMP/out" 3 8); e0=$(csv_value "$TMP/out" 1 8)
r=$(awk -v a="$e2" -v b="$e1" 'BEGIN { print a / b }')
if close "$r" 8 0.02 && close "$e0" 0 1e-14; then ok "taylor2 max error O(beta^3) (ratio $r), 0 at beta 0"; else notok "taylor2 ratio $r, e0 $e0"; fi
expect_success "taylor-error json" taylor-error --order 8 --taylor 1.5 --beta 25 --degrees --format json
if grep -q '"convention"' "$TMP/out" && grep -q '"order": *8,' "$TMP/out" && grep -q '"lobe"' "$TMP/out"; then ok "taylor-error json fields"; else notok "taylor-error json fields"; fi
expect_usage_error "taylor-error no taylor" taylor-error --order 5 --beta 0.1
expect_usage_error "taylor-error bad taylor" taylor-error --order 5 --taylor 3 --beta 0.1
expect_usage_error "taylor-error both beta forms" taylor-error --order 5 --taylor 1 --beta 0.1 --beta-max 1 --steps 2
expect_usage_error "taylor-error beta-max without steps" taylor-error --order 5 --taylor 1 --beta-max 1
expect_usage_error "taylor-error beta out of range" taylor-error --order 5 --taylor 1 --beta 200 --degrees
expect_usage_error "taylor-error negative lobe exponent" taylor-error --order 5 --taylor 1 --beta 0.1 --lobe-exp -1

# the methods work through rotmat/rotate
for m in taylor1 taylor1.5 taylor2; do
    expect_success "rotate --method $m" rotate --order 3 --method $m --euler 0.1,0.05,0.2 --coeffs 1,0,0.5,0,0,0,0,0,0.25 --precision float
done
