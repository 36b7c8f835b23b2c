#!/bin/sh
# The kernels (--kernel): the generated file is what its generator writes;
# every kernel this machine runs passes the golden fixtures in double and
# float, from the fixture's angles and from its matrix; the option is
# refused cleanly where it must be.
. tests/cli/lib.inc
FX=data/fixtures/rotation
BUILD=${BUILD:-build}
GEN_FILE=src/rotate/rot_unrolled_gen.h

# regenerating reproduces the committed file (the command is in its banner)
cmd=$(sed -n 's|^ \*   build/tools/gen_rot_unrolled \(.*\) > src/rotate/rot_unrolled_gen.h$|\1|p' $GEN_FILE)
if [ -x "$BUILD/tools/gen_rot_unrolled" ] && [ -n "$cmd" ]; then
    # shellcheck disable=SC2086
    "$BUILD/tools/gen_rot_unrolled" $cmd >"$TMP/gen.h" 2>"$TMP/gen.err"
    if cmp -s "$TMP/gen.h" $GEN_FILE; then ok "$GEN_FILE is what 'gen_rot_unrolled $cmd' writes"
    else notok "$GEN_FILE differs from the generator's output (run make regen): $(diff $GEN_FILE "$TMP/gen.h" | head -5)"; fi
else
    notok "generator $BUILD/tools/gen_rot_unrolled or its command in the banner missing"
fi
if grep -q 'DO NOT EDIT' $GEN_FILE; then ok "banner says DO NOT EDIT"; else notok "no DO NOT EDIT banner"; fi

expect_usage_error "rotate --kernel bogus" rotate --method zxzxz --euler 0.1,0.2,0.3 --coeffs 1,0,0,0 --kernel bogus
expect_usage_error "bench --kernel bogus" bench --order 3 --methods zxzxz --kernel bogus
expect_usage_error "bench --input bogus" bench --order 3 --methods zxzxz --input bogus
expect_usage_error "verify --kernel without --method" verify --fixture $FX/orders_1_10.json --candidate x.json --kernel scalar

for k in scalar unrolled sse2 avx2 avx512; do
    "$SHLAB" rotate --method zxzxz --euler 0.1,0.2,0.3 --coeffs 1,0,0,0 --kernel $k >"$TMP/out" 2>"$TMP/err"; rc=$?
    if [ "$rc" = 2 ] && grep -q "not available" "$TMP/err"; then
        ok "kernel $k is not available on this machine: refused with a clear error"
        continue
    fi
    for p in double float; do
        for in in "" --matrix-input; do
            expect_success "verify zxzxz $p --kernel $k $in" verify --fixture $FX/orders_1_10.json --method zxzxz --precision $p --kernel $k $in
            expect_success "verify taylor1.5 $p --kernel $k $in" verify --fixture $FX/orders_1_10_taylor1.5.json --method taylor1.5 --precision $p --kernel $k $in
        done
    done
    # the matrix form of a rotation gives what its angles give
    "$SHLAB" rotmat --order 4 --method zxzxz --euler 0.3,1.1,-2 --kernel $k --format csv >"$TMP/e" 2>/dev/null
    # R = Rz(a) Ry(b) Rz(g) written out (docs/CONVENTIONS.md), to 17 digits
    R=$(awk 'BEGIN { a = 0.3; b = 1.1; g = -2; ca = cos(a); sa = sin(a); cb = cos(b); sb = sin(b); cg = cos(g); sg = sin(g);
        printf "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", ca*cb*cg - sa*sg, -ca*cb*sg - sa*cg, ca*sb,
               sa*cb*cg + ca*sg, -sa*cb*sg + ca*cg, sa*sb, -sb*cg, sb*sg, cb }')
    "$SHLAB" rotmat --order 4 --method zxzxz --matrix "$R" --kernel $k --format csv >"$TMP/m" 2>/dev/null
    if [ -s "$TMP/e" ] && [ -s "$TMP/m" ] && paste -d, "$TMP/e" "$TMP/m" | awk -F, 'NR > 1 { h = NF / 2; for (i = 1; i <= h; i++) if ($i ~ /^-?[0-9]/) { d = $i - $(i + h); if (d < 0) d = -d; if (d > 1e-13) bad = 1 } } END { exit bad }'; then
        ok "rotmat --kernel $k: --matrix equals --euler"
    else
        notok "rotmat --kernel $k: --matrix differs from --euler"
    fi
done

# the other exact methods from the matrix (ivanic: unrolled to order 6, then
# loops; blanco: no angle either)
for m in ivanic blanco choi; do
    for p in double float; do
        expect_success "verify $m $p --matrix-input" verify --fixture $FX/orders_1_10.json --method $m --precision $p --matrix-input
    done
done

# the bench's kernel, input and k-rotations options
expect_success "bench k-rotations" bench --order 4 --methods zxzxz,ivanic --mode k-rotations --batch 9 --count 3 --repeat 1 --quiet --format csv
if grep -q 'k-rotations' "$TMP/out" && head -1 "$TMP/out" | grep -q 'kernel,input'; then ok "bench rows name mode, kernel and input"; else notok "bench k-rotations rows: $(head -2 "$TMP/out")"; fi
expect_success "bench scalar vs unrolled, euler vs matrix" bench --order 3 --methods zxzxz --kernel scalar,unrolled --input euler,matrix --mode per-rotation --count 3 --repeat 1 --quiet --format csv
rows=$(($(wc -l <"$TMP/out") - 1))
if [ "$rows" = 4 ]; then ok "bench: 2 kernels x 2 inputs = 4 rows"; else notok "bench: $rows rows"; fi
