#!/bin/sh
# test_rough_edges.sh — what a newcomer ran into: help texts that point inside
# the repository, one wording for a bad order, fixtures that check their
# outputs before computing and write all or nothing, verify's messages for a
# missing file and for --diagnose, --simulate's exit status, the
# orthonormality check, experiment binaries that answer --help.
. "$(dirname "$0")/lib.inc"
BUILD=${BUILD:-build}
FX=data/fixtures/rotation

# ---- every help text points at the conventions document in the repository
cmds=$("$SHLAB" --help | awk '/^Commands:/ { on = 1; next } on && /^  [a-z]/ { print $1 } on && /^$/ { on = 0 }')
bad=""
for c in $cmds; do
    "$SHLAB" "$c" --help >"$TMP/h" 2>&1 || bad="$bad $c(exit)"
    grep -q 'docs/CONVENTIONS.md' "$TMP/h" || bad="$bad $c"
    grep -Eq '\.\./shared|READING\.md|issue [0-9]' "$TMP/h" && bad="$bad $c(outside)"
done
[ -n "$cmds" ] && [ -z "$bad" ] && ok "every --help names docs/CONVENTIONS.md, nothing outside the repository" || notok "help texts:$bad"
[ -f docs/CONVENTIONS.md ] && ok "docs/CONVENTIONS.md exists" || notok "docs/CONVENTIONS.md missing"

# ---- one wording for an order out of range, lists included (each command
# names its own limit: tests/cli/test_hostile_inputs.sh)
"$SHLAB" rotmat --order 0 --euler 0,0,0 2>"$TMP/a" >/dev/null
for c in "bench --order 0" "bench --order 2,0"; do
    "$SHLAB" $c 2>"$TMP/b" >/dev/null
    cmp -s "$TMP/a" "$TMP/b" && ok "'$c' words the error as rotmat --order 0" || notok "$c: $(cat "$TMP/b") vs $(cat "$TMP/a")"
done
"$SHLAB" plan --order 0 --max-beta 0 --tolerance 1 2>"$TMP/b" >/dev/null
sed 's/4097/64/' "$TMP/a" | cmp -s - "$TMP/b" && ok "plan --order 0: the same words with plan's limit 64" || notok "plan: $(cat "$TMP/b")"
expect_usage_error "bench --order x" bench --order 2,x

# ---- fixtures: outputs checked before computing, all or nothing
expect_usage_error "fixtures --out /nonexistent/dir" fixtures --out "$TMP/nonexistent/dir"
grep -q "nonexistent/dir/orders_1_10.json" "$TMP/err" && ok "fixtures names the target it cannot write" || notok "$(cat "$TMP/err")"
mkdir -p "$TMP/D/bands_50_200.json"
echo old >"$TMP/D/orders_1_10.json"
expect_usage_error "fixtures --out D with D/bands_50_200.json a directory" fixtures --out "$TMP/D"
[ "$(cat "$TMP/D/orders_1_10.json")" = old ] && [ "$(ls "$TMP/D" | wc -l)" = 2 ] \
    && ok "nothing written or left behind (orders_1_10.json untouched, no temporary file)" || notok "D holds: $(ls -a "$TMP/D")"
touch "$TMP/file"
expect_usage_error "fixtures --out a regular file" fixtures --out "$TMP/file" --method taylor1.5

# ---- verify: a missing file, --diagnose's two tolerances, --simulate
expect_usage_error "verify missing fixture" verify --fixture "$TMP/none.json" --method zxzxz
grep -q "^shlab: error: cannot open fixture '.*none.json': No such file or directory$" "$TMP/err" \
    && ok "missing fixture: 'cannot open fixture', no '(line -1)'" || notok "$(cat "$TMP/err")"
expect_usage_error "verify missing candidate" verify --fixture $FX/orders_1_10.json --candidate "$TMP/none.json"
grep -q "cannot open candidate" "$TMP/err" && ! grep -q 'line -1' "$TMP/err" && ok "missing candidate: 'cannot open candidate'" || notok "$(cat "$TMP/err")"
expect_usage_error "verify fixture is a directory" verify --fixture "$TMP" --method zxzxz
"$SHLAB" verify --fixture $FX/orders_1_10.json --method zxzxz --emit-candidate "$TMP/inv.json" --simulate inverse --format json >"$TMP/out" 2>"$TMP/err"; rc=$?
[ $rc = 0 ] && [ -s "$TMP/inv.json" ] && grep -q '"simulated":"inverse"' "$TMP/out" && grep -q '"pass":false' "$TMP/out" \
    && ok "--simulate inverse: exit 0, candidate written, the simulated kernel's verdict printed" || notok "simulate: rc $rc $(cat "$TMP/err")"
"$SHLAB" verify --fixture $FX/orders_1_10.json --candidate "$TMP/inv.json" --diagnose --format json >"$TMP/out" 2>"$TMP/err"; rc=$?
f=$(sed -n 's/.*"failed":\([0-9]*\).*/\1/p' "$TMP/out"); c=$(sed -n 's/.*"diagnosis_checked":\([0-9]*\).*/\1/p' "$TMP/out")
[ $rc = 1 ] && grep -q '"diagnosis":"inverse rotation' "$TMP/out" && grep -q '"diagnosis_tolerance":"float32"' "$TMP/out" \
    && grep -q "the diagnosis compares at each case's float32 tolerance: diagnosis_checked = the $c cases" "$TMP/err" \
    && grep -q "of the $f failed cases are within their float32 tolerance" "$TMP/err" \
    && ok "--diagnose says what failed ($f) and diagnosis_checked ($c) count" || notok "diagnose: rc $rc $(cat "$TMP/err")"

# ---- orthonormality: Gauss-Legendre with S θ nodes is exact up to order S
expect_success "orthonormality --help" orthonormality --help
"$SHLAB" orthonormality --order 6 --rule quad --samples 6 --format json >"$TMP/out" 2>"$TMP/err"; rc=$?
[ $rc = 0 ] && grep -q '"orthonormal":true' "$TMP/out" && grep -q '"exact_to_order":6' "$TMP/out" \
    && ok "quad S = 6 is orthonormal at order 6 (exit 0)" || notok "quad 6: rc $rc $(head -c 300 "$TMP/out")"
"$SHLAB" orthonormality --order 6 --rule quad --samples 5 --format json >"$TMP/out" 2>"$TMP/err"; rc=$?
[ $rc = 1 ] && grep -q '"orthonormal":false' "$TMP/out" && grep -q '"exact_to_order":5' "$TMP/out" \
    && ok "quad S = 5 fails at order 6, exact to order 5 (exit 1)" || notok "quad 5: rc $rc $(head -c 300 "$TMP/out")"
"$SHLAB" orthonormality --order 4 --rule random --samples 1000 --seed 3 --format csv >"$TMP/out" 2>"$TMP/err"; rc=$?
e=$(awk -F, 'NR == 5 { print $NF }' "$TMP/out")
[ $rc = 1 ] && awk -v e="$e" 'BEGIN { exit !(e > 1e-3 && e < 0.5) }' && ok "random rule, 1000 nodes: order-4 error $e (1/√N scale)" \
    || notok "random: rc $rc $(cat "$TMP/out")"
expect_usage_error "orthonormality order 65" orthonormality --order 65
expect_usage_error "orthonormality bad rule" orthonormality --order 4 --rule simpson
expect_usage_error "orthonormality too many nodes" orthonormality --order 4 --samples 5000

# ---- experiment binaries answer --help without running
if make -s "$BUILD/experiments/orthonormality" >"$TMP/log" 2>&1; then
    mkdir -p "$TMP/exp"; cd "$TMP/exp" || exit 1
    "$OLDPWD/$BUILD/experiments/orthonormality" --help >"$TMP/out" 2>"$TMP/err"; rc=$?
    [ $rc = 0 ] && grep -q '^Usage: orthonormality OUTDIR' "$TMP/out" && [ -z "$(ls -A "$TMP/exp")" ] \
        && ok "experiment --help: usage, exit 0, nothing written" || notok "experiment --help: rc $rc, $(ls -A "$TMP/exp")"
    "$OLDPWD/$BUILD/experiments/orthonormality" --bogus >"$TMP/out" 2>"$TMP/err"; rc=$?
    [ $rc = 2 ] && [ -z "$(ls -A "$TMP/exp")" ] && ok "experiment with an unknown option: exit 2, nothing written" || notok "rc $rc"
    cd "$OLDPWD" || exit 1
else
    notok "cannot build $BUILD/experiments/orthonormality: $(tail -3 "$TMP/log")"
fi

# ---- no silent wrong results: out-of-domain values refused, not replaced
expect_usage_error "shadow-field --cone-angle -1 (was silently 45°)" shadow-field --scene sphere-plane --cone-angle -1 --res 2
expect_usage_error "shadow-field --cone-angle 0" shadow-field --scene sphere-plane --cone-angle 0 --res 2
expect_usage_error "render with a light whose square overflows" render --scene bowl --res 4 --light const:1e308 --rays 16 --width 16 --height 12 --quiet --out "$TMP/big.exr" --error-png "$TMP/big.png"
expect_usage_error "scene-plan with a light whose square overflows" scene-plan --scene bowl --light const:1e300 --budget 0.1 --quiet
[ ! -e "$TMP/big.exr" ] && [ ! -e "$TMP/big.png" ] && ok "nothing written for the refused render" || notok "a refused render wrote files"
"$SHLAB" reconstruct --order 1 --coeffs 1 --width 2 --out "$TMP/one.exr" >/dev/null 2>&1
expect_usage_error "project: a 2×1 image cannot carry order 2" project --order 2 --exr "$TMP/one.exr"
expect_success "project: a 2×1 image carries order 1" project --order 1 --exr "$TMP/one.exr" --format json
# the image is y_0^0 = 1/√(4π) everywhere (reconstructed from c0 = 1, float
# pixels): its order-1 projection gives back c0 = 1 to float precision
c0=$(tr -d ' \n' <"$TMP/out" | sed -n 's/.*"Y":\[\([^],]*\).*/\1/p')
close "$c0" 1 1e-6 && ok "order-1 projection of a constant image gives its coefficient back" || notok "c0 = $c0"
"$SHLAB" reconstruct --order 1 --coeffs 1 --width 12 --out "$TMP/small.exr" >/dev/null 2>&1
"$SHLAB" plan --order auto --exr "$TMP/small.exr" --tolerance 1e-3 --max-beta 0.1 --quiet --format json >"$TMP/out" 2>"$TMP/err"
grep -q '"order": *1' "$TMP/out" && ok "plan --order auto stays within what the image carries" || notok "plan auto: $(head -c 300 "$TMP/out") $(cat "$TMP/err")"
