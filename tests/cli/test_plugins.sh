#!/bin/sh
# Plug-in kernels (shlab/kernel.h; tests/plugins/kernels.c, built by make
# check): `verify --plugin` gives the same verdict as `--candidate` on the
# plug-in's own outputs, names each deliberate mistake as the simulated
# candidate's diagnosis does, and reports a kernel that crashes, hangs,
# writes out of bounds or declines orders — with exit 1, one line, and the
# run finished.  The correct kernel (Ivanic and Ruedenberg's recurrence,
# written in the plug-in independently of shlab) passing every case is
# itself a check of both against the MPFR fixtures.
. tests/cli/lib.inc
FX=data/fixtures/rotation/orders_1_10.json
SO=${PLUGIN_SO:-${BUILD:-build}/tests/plugins/kernels.so}
[ -f "$SO" ] || { notok "plug-in $SO not built (make check builds it)"; exit 0; }

# field NAME of the JSON in file F (strings unquoted; null → null)
field() { sed -n "s/.*\"$2\":\(\"\([^\"]*\)\"\|\([^,}]*\)\).*/\2\3/p" "$1"; }

# plugin_vs_candidate SYMBOL ABI [ARGS...]: verify the plug-in (json, with
# --emit-candidate), then its candidate file (at the ABI's tolerance); exit
# codes and verdict fields (failed, pass, worst_id, worst_index, skipped,
# diagnosis) must agree.
plugin_vs_candidate() {
    sym=$1; abi=$2; shift 2
    case $abi in *-f) prec=float ;; *) prec=double ;; esac
    "$SHLAB" verify --quiet --fixture $FX --plugin "$SO:$sym" --abi "$abi" --emit-candidate "$TMP/c.json" \
        --diagnose --format json "$@" >"$TMP/p.json" 2>/dev/null; rc_p=$?
    "$SHLAB" verify --quiet --fixture $FX --candidate "$TMP/c.json" --convention cs --precision $prec --diagnose \
        --format json "$@" >"$TMP/c.out" 2>/dev/null; rc_c=$?
    same=1
    for f in failed pass worst_id worst_index skipped diagnosis; do
        [ "$(field "$TMP/p.json" $f)" = "$(field "$TMP/c.out" $f)" ] || same=0
    done
    if [ "$rc_p" = "$rc_c" ] && [ "$same" = 1 ]; then
        ok "$sym ($abi): plug-in and candidate agree (exit $rc_p, failed $(field "$TMP/p.json" failed))"
    else
        notok "$sym ($abi): plug-in exit $rc_p $(head -c 300 "$TMP/p.json") / candidate exit $rc_c $(head -c 300 "$TMP/c.out")"
    fi
}

expect_refused "--plugin without --abi" 'needs --abi' verify --fixture $FX --plugin "$SO:rot_matrix_d"
expect_refused "--abi unknown" 'abi' verify --fixture $FX --plugin "$SO:rot_matrix_d" --abi matrix-q
expect_refused "--plugin no symbol part" 'LIB.so:SYMBOL' verify --fixture $FX --plugin "$SO" --abi matrix-d
expect_refused "--plugin missing library" 'cannot open' verify --fixture $FX --plugin "$TMP/none.so:f" --abi matrix-d
expect_refused "--plugin missing symbol" "no symbol 'nosuch'" verify --fixture $FX --plugin "$SO:nosuch" --abi matrix-d
printf 'not an ELF file' >"$TMP/fake.so"
expect_refused "--plugin not a shared library" 'cannot load the plug-in' verify --fixture $FX --plugin "$TMP/fake.so:f" --abi matrix-d
expect_refused "--plugin and --method" 'exactly one' verify --fixture $FX --plugin "$SO:rot_matrix_d" --abi matrix-d --method zxzxz
expect_refused "--timeout without --plugin" 'timeout' verify --fixture $FX --method zxzxz --timeout 3
expect_refused "--orders malformed" 'orders' verify --fixture $FX --method zxzxz --orders 3-1
expect_refused "--cases unknown id" "no case 'nope'" verify --fixture $FX --method zxzxz --cases nope

# the correct kernel in every ABI passes every cs case; the nocs variant every nocs case
ncs=$(grep -c '"convention":"cs"' $FX)
for sa in rot_matrix_d:matrix-d rot_matrix_f:matrix-f rot_quat_d:quat-d rot_euler_d:euler-d \
          rot_matrix_batch_d:matrix-batch-d; do
    sym=${sa%%:*}; abi=${sa#*:}
    "$SHLAB" verify --quiet --fixture $FX --plugin "$SO:$sym" --abi "$abi" --format json >"$TMP/p.json" 2>"$TMP/err"; rc=$?
    run=$(( $(field "$TMP/p.json" cases) - $(field "$TMP/p.json" skipped) ))
    if [ "$rc" = 0 ] && [ "$(field "$TMP/p.json" pass)" = true ] && [ "$run" = "$ncs" ]; then
        ok "$sym ($abi): the $run cs cases pass ($(field "$TMP/p.json" tolerance_kind) tolerance)"
    else notok "$sym ($abi): exit $rc, $(head -c 300 "$TMP/p.json") $(head -c 200 "$TMP/err")"; fi
done
"$SHLAB" verify --quiet --fixture $FX --plugin "$SO:rot_matrix_d_nocs" --abi matrix-d --convention nocs --format json >"$TMP/p.json" 2>/dev/null; rc=$?
if [ "$rc" = 0 ] && [ "$(field "$TMP/p.json" convention)" = nocs ]; then ok "nocs kernel with --convention nocs passes"; else notok "nocs kernel: exit $rc"; fi
"$SHLAB" verify --quiet --fixture $FX --plugin "$SO:rot_matrix_d_nocs" --abi matrix-d --diagnose --format json >"$TMP/p.json" 2>/dev/null; rc=$?
if [ "$rc" = 1 ] && grep -q '"diagnosis":"other CS-phase convention' "$TMP/p.json"; then ok "nocs kernel given cs cases: diagnosed as the other convention"; else notok "nocs kernel as cs: exit $rc"; fi

# each deliberate mistake: the plug-in's diagnosis is the simulated candidate's
for ms in inverse:matrix-d:inverse convention:matrix-d:convention swap:euler-d:swap deg2rad:euler-d:deg2rad \
          rad2deg:euler-d:rad2deg mdesc:matrix-d:mdesc mdesc_out:matrix-d:mdesc-out mdesc_in:matrix-d:mdesc-in \
          float:matrix-d:float beta:euler-d:convention; do
    sym=mistake_${ms%%:*}; rest=${ms#*:}; abi=${rest%%:*}; sim=${rest#*:}
    "$SHLAB" verify --quiet --fixture $FX --method wigner --emit-candidate "$TMP/sim.json" --simulate "$sim" --convention cs >/dev/null 2>&1
    "$SHLAB" verify --quiet --fixture $FX --candidate "$TMP/sim.json" --convention cs --diagnose --format json >"$TMP/s.json" 2>/dev/null
    "$SHLAB" verify --quiet --fixture $FX --plugin "$SO:$sym" --abi "$abi" --diagnose --format json >"$TMP/p.json" 2>/dev/null; rc=$?
    want=$(field "$TMP/s.json" diagnosis); got=$(field "$TMP/p.json" diagnosis)
    if [ "$rc" = 1 ] && [ -n "$want" ] && [ "$got" = "$want" ] && [ "$want" != "no known transformation explains the mismatch" ]; then
        ok "$sym: diagnosed as the simulated '$sim': $got"
    else notok "$sym: exit $rc, plug-in '$got', simulated '$want'"; fi
    plugin_vs_candidate "$sym" "$abi"
done
plugin_vs_candidate rot_matrix_d matrix-d
plugin_vs_candidate rot_matrix_f matrix-f
# a candidate file holds numbers: the outputs of failed calls are not written
expect_refused "--emit-candidate of a kernel that failed" "non-finite" verify --quiet --fixture $FX --plugin "$SO:fails_order_5" --abi matrix-d --emit-candidate "$TMP/c5.json"
if [ ! -e "$TMP/c5.json" ]; then ok "no candidate file left"; else notok "a candidate file was written"; fi

# orders 1..6 only: the cases above are declined and reported as not run;
# --orders gives a candidate without them the same verdict
n7=$(grep '"convention":"cs"' $FX | grep -c '"order":\(7\|8\|9\|10\),')
"$SHLAB" verify --quiet --fixture $FX --plugin "$SO:orders_1_6" --abi matrix-d --emit-candidate "$TMP/c6.json" --format json >"$TMP/p.json" 2>/dev/null; rc=$?
if [ "$rc" = 0 ] && grep -q "\"skipped_why\":\"[^\"]*$n7 declined by the kernel" "$TMP/p.json"; then ok "orders_1_6: passes, $n7 cases declined"; else notok "orders_1_6: exit $rc $(cat "$TMP/p.json")"; fi
expect_refused "candidate without orders 7-10, all cases asked" "case 'o7-[^']*' missing" verify --fixture $FX --candidate "$TMP/c6.json"
expect_success "candidate without orders 7-10, --orders 1-6 --convention cs" verify --fixture $FX --candidate "$TMP/c6.json" --orders 1-6 --convention cs
"$SHLAB" verify --quiet --fixture $FX --candidate "$TMP/c6.json" --cases o1-beta=0-cs,o6-random1-cs --format json >"$TMP/p.json" 2>/dev/null; rc=$?
if [ "$rc" = 0 ] && [ "$(field "$TMP/p.json" skipped)" = $(( $(grep -c '"id"' $FX) - 2 )) ]; then ok "--cases runs exactly the two cases"; else notok "--cases: exit $rc $(cat "$TMP/p.json")"; fi

# kernels that misbehave: exit 1, one line naming what happened and where,
# the report still printed, shlab unharmed
misbehave() {
    sym=$1; re=$2; shift 2
    "$SHLAB" verify --quiet --fixture $FX --plugin "$SO:$sym" --abi matrix-d --format json "$@" >"$TMP/p.json" 2>"$TMP/err"; rc=$?
    if [ "$rc" = 1 ] && grep -Eq "\"kernel_failure\":\"$re" "$TMP/p.json" && grep -Eq "^verify: $re" "$TMP/err" &&
       [ "$(field "$TMP/p.json" pass)" = false ]; then
        ok "$sym: $(field "$TMP/p.json" kernel_failure)"
    else notok "$sym: exit $rc, $(head -c 300 "$TMP/p.json") $(head -c 300 "$TMP/err")"; fi
}
misbehave crash_order_4 "the kernel crashed \(SIGSEGV[^\"]*\) on case 'o4-"
misbehave hang_order_3 "the kernel did not return within 2 s on case 'o3-" --timeout 2
misbehave writes_past_output "the kernel wrote past the end of its output \(guard page\) on case 'o1-"
misbehave writes_before_output "the kernel wrote before the start of its output on case 'o1-"
misbehave writes_input "the kernel wrote to its input \(read-only\) on case 'o1-"
misbehave reads_past_input "the kernel read past the end of its input \(guard page\) on case 'o1-"
# the cases done before the crash are judged: the cs cases before the first
# cs case of order 4 in the file ran and passed
"$SHLAB" verify --quiet --fixture $FX --plugin "$SO:crash_order_4" --abi matrix-d --format json >"$TMP/p.json" 2>/dev/null
nbefore=$(grep '"convention":"cs"' $FX | awk '/"order":4,/ { exit } { n++ } END { print n + 0 }')
run=$(( $(field "$TMP/p.json" cases) - $(field "$TMP/p.json" skipped) ))
if [ "$run" = "$nbefore" ] && [ "$(field "$TMP/p.json" failed)" = 0 ]; then ok "crash at order 4: the $nbefore cases before it judged, none failed"; else notok "crash: run $run, want $nbefore"; fi
# a failure code fails its cases, and is counted
"$SHLAB" verify --quiet --fixture $FX --plugin "$SO:fails_order_5" --abi matrix-d --format json >"$TMP/p.json" 2>/dev/null; rc=$?
n5=$(grep '"convention":"cs"' $FX | grep -c '"order":5,')
if [ "$rc" = 1 ] && [ "$(field "$TMP/p.json" kernel_errors)" = "$n5" ] && [ "$(field "$TMP/p.json" failed)" = "$n5" ]; then ok "fails_order_5: $n5 failure codes, $n5 cases failed"; else notok "fails_order_5: exit $rc $(cat "$TMP/p.json")"; fi
# an output left unwritten (it starts as NaN) fails
"$SHLAB" verify --quiet --fixture $FX --plugin "$SO:skips_last_output" --abi matrix-d --format json >"$TMP/p.json" 2>/dev/null; rc=$?
if [ "$rc" = 1 ] && [ "$(field "$TMP/p.json" worst_got)" = "not finite" ]; then ok "an unwritten output fails as not finite"; else notok "skips_last_output: exit $rc $(cat "$TMP/p.json")"; fi
