#!/bin/sh
# test_convention_tags.sh — every result carries "convention" (and "method"
# where one is run); bench, plan and euler accept --convention.
. "$(dirname "$0")/lib.inc"
FX=data/fixtures/rotation

# euler: accepts --convention and echoes it (angles do not depend on it)
expect_success "euler --convention nocs" euler --matrix 0,-1,0,1,0,0,0,0,1 --convention nocs --format json
grep -q '"convention":"nocs"' "$TMP/out" && ok "euler json: convention nocs" || notok "euler: $(cat "$TMP/out")"
expect_success "euler default convention" euler --euler 0.1,0.2,0.3 --format json
grep -q '"convention":"cs"' "$TMP/out" && ok "euler json: convention cs by default" || notok "euler: $(cat "$TMP/out")"
expect_usage_error "euler bad convention" euler --euler 0.1,0.2,0.3 --convention xyz

# bench: the plans timed are in the convention asked for, and say so
expect_success "bench --convention nocs" bench --order 3 --methods zxzxz --mode per-rotation --convention nocs --count 10 --repeat 1 --quiet --format json
grep -q '"convention":"nocs"' "$TMP/out" && ok "bench json: convention nocs" || notok "bench: $(head -c 200 "$TMP/out")"
expect_usage_error "bench bad convention" bench --order 3 --methods zxzxz --convention xyz

# plan in nocs: methods and the MPFR truth both in nocs, so the exact ones
# still agree to rounding (a convention mix-up would give errors of order 1)
expect_success "plan --convention nocs" plan --order 4 --max-beta 10 --degrees --tolerance 1e-12 --error max --beta-step 2 --convention nocs --quiet --format json
grep -q '"convention":"nocs"' "$TMP/out" && grep -q '"choice":{"method"' "$TMP/out" \
    && ok "plan json: convention nocs, an exact method qualifies at 1e-12" || notok "plan nocs: $(head -c 300 "$TMP/out")"
expect_usage_error "plan bad convention" plan --order 4 --max-beta 0.1 --tolerance 1e-3 --convention xyz

# verify: "convention" from the fixture's cases; "method" with --method
expect_success "verify --method zxzxz" verify --fixture "$FX/orders_1_10.json" --method zxzxz --format json
want=$(grep -q '"convention": *"nocs"' "$FX/orders_1_10.json" && grep -q '"convention": *"cs"' "$FX/orders_1_10.json" && echo cs+nocs)
grep -q "\"convention\":\"${want:-?}\"" "$TMP/out" && grep -q '"method":"zxzxz"' "$TMP/out" && grep -q '"source":"zxzxz"' "$TMP/out" \
    && ok "verify json: convention $want, method and source zxzxz" || notok "verify: $(head -c 300 "$TMP/out")"
"$SHLAB" verify --fixture "$FX/orders_1_10.json" --method ivanic --emit-candidate "$TMP/cand.json" --format json >/dev/null 2>&1
expect_success "verify --candidate" verify --fixture "$FX/orders_1_10.json" --candidate "$TMP/cand.json" --format json
grep -q '"convention":"cs+nocs"' "$TMP/out" && ! grep -q '"method"' "$TMP/out" \
    && ok "verify candidate json: convention, no method" || notok "verify candidate: $(head -c 300 "$TMP/out")"
