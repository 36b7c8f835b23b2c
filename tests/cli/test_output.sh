#!/bin/sh
# test_output.sh — cosmetic contract of the output: no negative zeros in
# printed numbers, error messages name the command once.
. "$(dirname "$0")/lib.inc"

# a rotation by 90° about z: its exact entries are 0, ±1 (some computed as −0)
expect_success "rotmat 90 deg about z" rotmat --order 2 --method zxzxz --matrix 0,-1,0,1,0,0,0,0,1 --orthonormalize --format json
grep -Eq -- '-0(\.0+)?([],}]|e)' "$TMP/out" && notok "rotmat json has a negative zero: $(cat "$TMP/out")" || ok "rotmat json: no -0"
expect_success "rotmat 90 deg about z csv" rotmat --order 2 --method zxzxz --matrix 0,-1,0,1,0,0,0,0,1 --orthonormalize --format csv
grep -Eq -- '(^|,)-0(,|$)' "$TMP/out" && notok "rotmat csv has -0: $(cat "$TMP/out")" || ok "rotmat csv: no -0"

# scale-interp errors: "scale-interp: " once
for args in "--kmin 2 --kmax 1 --family cone" "--kmin -0.5 --kmax 1.5 --family midrange"; do
    expect_usage_error "scale-interp $args" scale-interp --order 4 --samples 10 --spacing uniform $args
    [ "$(grep -o 'scale-interp: ' "$TMP/err" | wc -l)" = 1 ] && ok "scale-interp error prefix once" || notok "prefix: $(cat "$TMP/err")"
done
