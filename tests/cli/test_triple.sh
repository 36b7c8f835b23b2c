#!/bin/sh
# CLI contract of `shlab triple` (Green 2003, eq. 8).
. tests/cli/lib.inc

expect_success "triple --help" triple --help
expect_usage_error "triple no order" triple --light green
expect_usage_error "triple no light" triple --order 3
expect_usage_error "triple order 0" triple --order 0 --light green
expect_usage_error "triple order too large" triple --order 1000 --light green
expect_usage_error "triple bad light" triple --order 3 --light nope
expect_usage_error "triple NaN cap" triple --order 3 --light cap:nan
expect_usage_error "triple unknown option" triple --order 3 --light green --bogus

# M for a constant light c is c·I (orthonormality), independent of the basis
expect_success "triple const:2" triple --order 3 --light const:2 --format csv
bad=$(awk -F, 'NR > 1 { r = $(NF-9); for (c = 0; c < 9; c++) { v = $(NF-8+c); e = (c == r) ? 2 : 0; d = v - e; if (d < 0) d = -d; if (d > 1e-14) print r, c, v } }' "$TMP/out")
if [ -z "$bad" ]; then ok "const:2 gives 2·I"; else notok "const:2 entries off: $bad"; fi
# M is symmetric for any light (here the kinked Green light)
expect_success "triple green" triple --order 3 --light green --format csv
asym=$(awk -F, 'NR > 1 { r = $(NF-9); for (c = 0; c < 9; c++) M[r, c] = $(NF-8+c) } END { w = 0; for (i = 0; i < 9; i++) for (j = 0; j < 9; j++) { d = M[i, j] - M[j, i]; if (d < 0) d = -d; if (d > w) w = d } print w }' "$TMP/out")
if close "$asym" 0 1e-15; then ok "green matrix symmetric ($asym)"; else notok "green matrix asymmetry $asym"; fi
# M_00 = ∫ b y_0 y_0 = mean of b = c_0/sqrt(4π); for cap:1, (1-cos 1)/2
expect_success "triple cap:1" triple --order 2 --light cap:1 --format csv
m00=$(awk -F, 'NR == 2 { print $(NF-3) }' "$TMP/out")
if close "$m00" "$(awk 'BEGIN { print (1 - cos(1)) / 2 }')" 1e-6; then ok "cap:1 M00 = cap area/4π"; else notok "cap:1 M00 = $m00"; fi
