#!/bin/sh
# test_hostile_inputs.sh — hostile inputs, second round: every refusal is
# exit 2 with exactly one line on stderr that says why (expect_refused:
# exit code, one line, the message's substance).
. "$(dirname "$0")/lib.inc"

# ---- numbers are decimal; list elements are never empty
expect_refused "--samples 0x10 is not 16" "--samples: cannot read a number at '0x10'" \
    shadow-field --light const:1 --samples 0x10
expect_refused "a hexadecimal light parameter" "cannot read a number at '0x1'" project --order 2 --light cap:0x1
expect_refused "a hexadecimal scene parameter" "bad number" transfer --scene sphere-plane:0x1p-1,1
expect_refused "--euler 0.1,,0.2 (an empty element is not dropped)" "--euler: empty element at character 5" \
    rotate --euler 0.1,,0.2 --coeffs 1
expect_refused "--coeffs with a trailing comma" "--coeffs: empty element" convert --from cs --to nocs --coeffs 1,0,0,0,
expect_refused "--coeffs with a leading comma" "--coeffs: empty element at character 1" convert --from cs --to nocs --coeffs ,1
expect_refused "bench --methods taylor1," "--methods: empty element" bench --methods taylor1, --order 2
expect_refused "bench --order 2,,3" "--order: empty element" bench --order 2,,3
expect_refused "cache --methods zxzxz,,ivanic" "--methods: empty element" cache --scene box-closed --light const:1 --methods zxzxz,,ivanic
printf '1, 2,\n, 3\n' >"$TMP/c.txt"
expect_refused "a coefficient file with an empty element" "empty element" rotate --euler 0,0,0 --in "$TMP/c.txt"
expect_success "spaces and commas still separate" convert --from cs --to nocs --coeffs " 1, 2 ,3 4" --format csv

# ---- an order out of range: the command's own limits
for c in "cache:32" "render:32" "transfer:32" "shadow-field:16" "triple:32" "deriv:32" "scale:32" \
         "orthonormality:64" "scale-interp:64" "scale-scene:16" "taylor-error:128" "rotate:4097" "eval:4097"; do
    cmd=${c%%:*}; max=${c##*:}
    expect_refused "$cmd --order 0 names $cmd's limit 1..$max" "--order: order 0 is outside 1\.\.$max( \(|$)" "$cmd" --order 0
    expect_refused "$cmd --order $((max + 1)) names $cmd's limit" "--order: order $((max + 1)) is outside 1\.\.$max( \(|$)" "$cmd" --order $((max + 1))
done
expect_refused "plan --order 65" "--order: order 65 is outside 1\.\.64$" plan --order 65 --max-beta 0 --tolerance 1
expect_refused "scene-plan --max-order 33" "--max-order: order 33 is outside 1\.\.32$" scene-plan --max-order 33
expect_refused "scale --verify at order 9" "--order: order 9 is outside 1\.\.8 \(with --verify" scale --order 9 --verify --family linear --k 2
