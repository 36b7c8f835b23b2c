#!/bin/sh
# test_units.sh — one meaning of --degrees in every command (angles in and
# angles out, each printed angle with a "unit" field), the shared warning for
# an angle in radians beyond 2π, and the warning for an approximate rotation
# beyond its accurate range (docs/CONVENTIONS.md "Angles and units").
# Truths: closed forms (a quarter turn about z), the same request in radians,
# and the Taylor error measured by `shlab taylor-error`.
. "$(dirname "$0")/lib.inc"
PI=3.141592653589793
# json_num FILE KEY: the first number after "KEY":
json_num() { sed -n "s/.*\"$2\":\([-0-9.eE+]*\).*/\1/p" "$1" | head -1; }
json_str() { sed -n "s/.*\"$2\":\"\([^\"]*\)\".*/\1/p" "$1" | head -1; }
# expect_warning "what" REGEX args... : exit 0, output on stdout, exactly one
# stderr line, a "shlab: warning: " line matching REGEX
expect_warning() {
    what=$1; re=$2; shift 2
    "$SHLAB" "$@" >"$TMP/out" 2>"$TMP/err"; rc=$?
    if [ "$rc" = 0 ] && [ -s "$TMP/out" ] && [ "$(wc -l <"$TMP/err")" = 1 ] \
        && grep -Eq "^shlab: warning: $re" "$TMP/err"; then ok "$what"
    else notok "$what (exit $rc: $(head -c 300 "$TMP/err"))"; fi
}
# expect_quiet "what" args... : exit 0 and nothing at all on stderr
expect_quiet() {
    what=$1; shift
    "$SHLAB" "$@" >"$TMP/out" 2>"$TMP/err"; rc=$?
    if [ "$rc" = 0 ] && [ ! -s "$TMP/err" ]; then ok "$what"; else notok "$what (exit $rc: $(head -c 300 "$TMP/err"))"; fi
}

# ---- euler: degrees out for every input form ------------------------------
# Rz(90°) as a matrix and as a quaternion: β = 0, α = 0, γ = 90° (README).
expect_success "euler --matrix --degrees" euler --matrix 0,-1,0,1,0,0,0,0,1 --degrees --format json
g=$(json_num "$TMP/out" gamma); b=$(json_num "$TMP/out" beta)
close "$g" 90 1e-13 && close "$b" 0 1e-13 && [ "$(json_str "$TMP/out" unit)" = degrees ] \
    && ok "euler --matrix --degrees: gamma 90, unit degrees" || notok "euler --matrix --degrees: $(cat "$TMP/out")"
expect_success "euler --quat --degrees" euler --quat 0.7071067811865476,0,0,0.7071067811865476 --degrees --format json
close "$(json_num "$TMP/out" gamma)" 90 1e-13 && ok "euler --quat --degrees: gamma 90" || notok "euler --quat: $(cat "$TMP/out")"
expect_success "euler --matrix radians" euler --matrix 0,-1,0,1,0,0,0,0,1 --format json
close "$(json_num "$TMP/out" gamma)" 1.5707963267948966 1e-15 && [ "$(json_str "$TMP/out" unit)" = radians ] \
    && ok "euler radians: gamma π/2, unit radians" || notok "euler radians: $(cat "$TMP/out")"
# in and out: --euler 30,60,-45 --degrees comes back as (30, 60, -45)
expect_success "euler --euler --degrees" euler --euler 30,60,-45 --degrees --format csv
[ "$(sed -n 2p "$TMP/out" | cut -d, -f1-4)" = "30,60,-45,degrees" ] && ok "euler round trip in degrees" \
    || notok "euler round trip: $(cat "$TMP/out")"
# rotmat and rotate take --degrees with --matrix/--quat too (no angle to convert)
expect_success "rotmat --matrix --degrees" rotmat --order 2 --matrix 0,-1,0,1,0,0,0,0,1 --degrees --method zxzxz --format csv
cp "$TMP/out" "$TMP/deg"
"$SHLAB" rotmat --order 2 --euler 0,0,90 --degrees --method zxzxz --format csv >"$TMP/eul" 2>/dev/null
d=$(paste -d, "$TMP/deg" "$TMP/eul" | awk -F, 'NR > 1 { h = NF / 2; for (i = 6; i <= h; i++) { x = $i - $(i + h); if (x < 0) x = -x; if (x > m) m = x } } END { print m + 0 }')
close "$d" 0 1e-15 && ok "rotmat --matrix Rz(90°) = --euler 0,0,90 --degrees" || notok "rotmat matrix vs euler: $d"

# ---- plan: max_beta and worst_beta in the unit asked for ------------------
expect_success "plan --degrees" plan --order 3 --max-beta 5 --degrees --tolerance 1e-3 --error max --beta-step 1 --quiet --format json
cp "$TMP/out" "$TMP/plan_deg"
b=$(json_num "$TMP/plan_deg" max_beta)
[ "$(json_str "$TMP/plan_deg" unit)" = degrees ] && close "$b" 5 1e-15 && ok "plan --degrees: max_beta 5, unit degrees" \
    || notok "plan --degrees: $(head -c 300 "$TMP/plan_deg")"
rad=$(awk -v p=$PI 'BEGIN { printf "%.17g", 5 * p / 180 }'); st=$(awk -v p=$PI 'BEGIN { printf "%.17g", p / 180 }')
expect_success "plan radians" plan --order 3 --max-beta "$rad" --tolerance 1e-3 --error max --beta-step "$st" --quiet --format json
cp "$TMP/out" "$TMP/plan_rad"
[ "$(json_str "$TMP/plan_rad" unit)" = radians ] && close "$(json_num "$TMP/plan_rad" max_beta)" "$rad" 1e-15 \
    && ok "plan radians: max_beta 5π/180, unit radians" || notok "plan radians: $(head -c 300 "$TMP/plan_rad")"
# the worst β of every candidate (candidates are sorted by time: match by method)
wb() { grep -o '"method":"[^"]*","exact":[a-z]*,"ok":[a-z]*,[^}]*"worst_beta":[-0-9.e]*' "$1" \
    | sed 's/"method":"\([^"]*\)".*"worst_beta":\(.*\)/\1 \2/' | sort; }
wb "$TMP/plan_deg" >"$TMP/wd"; wb "$TMP/plan_rad" >"$TMP/wr"
join "$TMP/wd" "$TMP/wr" | awk -v p=$PI '{ n++; if ($2 < 0 || $2 > 5 + 1e-12) bad = 1; d = $2 - $3 * 180 / p; if (d < 0) d = -d; if (d > 1e-9) bad = 1 }
    END { exit !(n >= 5 && !bad) }' \
    && ok "plan worst_beta: degrees = radians·180/π for every candidate" || notok "plan worst_beta: $(cat "$TMP/wd" "$TMP/wr" | tr '\n' ' ')"

# ---- taylor-error, deriv, stability, scale, light specs -------------------
expect_success "taylor-error --degrees" taylor-error --order 5 --taylor 1.5 --beta 10 --degrees --format json
[ "$(json_str "$TMP/out" unit)" = degrees ] && close "$(json_num "$TMP/out" beta)" 10 1e-15 \
    && ok "taylor-error: beta 10, unit degrees" || notok "taylor-error: $(cat "$TMP/out")"
expect_success "deriv --degrees" deriv --order 3 --k 1 --beta 30 --degrees --format csv
cp "$TMP/out" "$TMP/dd"
[ "$(sed -n 2p "$TMP/dd" | cut -d, -f3,4)" = "30,degrees" ] && ok "deriv: beta 30, unit degrees" || notok "deriv: $(head -2 "$TMP/dd")"
expect_success "deriv radians" deriv --order 3 --k 1 --beta 0.52359877559829882 --format csv
[ "$(sed -n 2p "$TMP/out" | cut -d, -f4)" = radians ] && cut -d, -f7- "$TMP/out" >"$TMP/dr" && cut -d, -f7- "$TMP/dd" >"$TMP/dd7" \
    && d=$(paste -d, "$TMP/dd7" "$TMP/dr" | awk -F, 'NR > 1 { h = NF / 2; for (i = 1; i <= h; i++) { x = $i - $(i + h); if (x < 0) x = -x; if (x > m) m = x } } END { print m + 0 }') \
    && close "$d" 0 1e-14 && ok "deriv: 30° and π/6 give the same matrix" || notok "deriv degrees vs radians"
expect_success "stability --degrees" stability --method zxzxz --bands 1 --degrees --format json
[ "$(json_str "$TMP/out" unit)" = degrees ] && grep -q '"name":"gimbal(pi/2,pi,pi/2)","euler":\[90.0,180.0,90.0\]' "$TMP/out" \
    && ok "stability --degrees: (π/2, π, π/2) printed as (90, 180, 90)" || notok "stability: $(head -c 400 "$TMP/out")"
expect_success "scale --cone-angle --degrees" scale --order 2 --family cone --k 0.5 --cone-angle 30 --degrees --format json
close "$(json_num "$TMP/out" cone_angle)" 30 1e-15 && [ "$(json_str "$TMP/out" unit)" = degrees ] \
    && ok "scale: cone_angle 30, unit degrees" || notok "scale: $(head -c 300 "$TMP/out")"
expect_success "scale default cone angle" scale --order 2 --family cone --k 0.5 --format json
close "$(json_num "$TMP/out" cone_angle)" 0.78539816339744828 1e-15 && [ "$(json_str "$TMP/out" unit)" = radians ] \
    && ok "scale: default cone_angle π/4 in radians" || notok "scale default: $(head -c 300 "$TMP/out")"
expect_success "scale-scene --degrees" scale-scene --scene cone --order 2 --k 2 --occluder-angle 30 --degrees --format json
close "$(json_num "$TMP/out" occluder_angle)" 30 1e-15 && close "$(json_num "$TMP/out" cone_family_angle)" 30 1e-15 \
    && [ "$(json_str "$TMP/out" unit)" = degrees ] && ok "scale-scene: angles 30, unit degrees" || notok "scale-scene: $(head -c 300 "$TMP/out")"
expect_success "project cap --degrees" project --order 2 --light cap:30 --degrees --format json
[ "$(json_str "$TMP/out" unit)" = degrees ] && ok "project cap:30 --degrees: unit degrees" || notok "project: $(cat "$TMP/out")"
expect_success "project const" project --order 2 --light const:1 --format json
grep -q '"unit"' "$TMP/out" && notok "project const has a unit field" || ok "project const: no angle, no unit field"

# ---- the 2π warning: one format for every command -------------------------
W='[a-z-]+: .* is more than 2π radians; degrees given without --degrees\?$'
expect_warning "rotmat --euler 90,0,0 warns" 'rotmat: --euler angle 90 is more than 2π radians; degrees given without --degrees\?$' rotmat --order 2 --euler 90,0,0
expect_quiet "rotmat --euler 90,0,0 --degrees: no warning" rotmat --order 2 --euler 90,0,0 --degrees
expect_warning "rotate --angle 90 warns" "$W" rotate --axis 1,0,0 --angle 90 --coeffs 1,0,0,0
expect_warning "euler --euler warns" "$W" euler --euler 0,0,-30
expect_warning "eval --theta warns" "$W" eval --order 2 --theta 100 --phi 0
expect_warning "deriv --beta warns" "$W" deriv --order 2 --k 1 --beta 400
expect_warning "project sun azimuth warns" "$W" project --order 2 --light cie-clear:0.5,90
expect_quiet "rotmat --euler 6,0,-6: no warning" rotmat --order 2 --euler 6,0,-6
# a warning never comes with an error: the error line stays alone
expect_usage_error "rotmat bad order and a big angle: one error line" rotmat --order 99 --euler 90,0,0

# ---- an approximate method beyond its range --------------------------------
# Taylor 1.5 at β = 60° (the README's newcomer case): the warning carries the
# lobe error that `shlab taylor-error` measures at the same β and order.
A='[a-z]+: taylor[0-9.]+ at β = [0-9.]+(°| rad) is beyond [0-9.e-]+(°| rad), where its lobe error reaches 1e-2; estimated lobe error here [0-9.e-]+'
expect_warning "rotate taylor1.5 at 60° warns" "$A" rotate --method taylor1.5 --euler 30,60,-45 --degrees --coeffs 0,0,0,0,0,1,0,0,0
est=$(sed -n 's/.*estimated lobe error here \([0-9.e-]*\) .*/\1/p' "$TMP/err")
lim=$(sed -n 's/.* is beyond \([0-9.e-]*\)°.*/\1/p' "$TMP/err")
"$SHLAB" taylor-error --order 3 --taylor 1.5 --beta 60 --degrees --format csv >"$TMP/te" 2>/dev/null
lobe=$(csv_value "$TMP/te" 1 10)
close "$est" "$lobe" 0.01 && ok "estimated error $est = taylor-error's lobe $lobe" || notok "estimate $est vs $lobe"
# the limit: the lobe error is <= 1e-2 just below it and > 1e-2 just above
lo=$(awk -v l="$lim" 'BEGIN { print l * 0.99 }'); hi=$(awk -v l="$lim" 'BEGIN { print l * 1.01 }')
"$SHLAB" taylor-error --order 3 --taylor 1.5 --beta "$lo" --degrees --format csv >"$TMP/a" 2>/dev/null
"$SHLAB" taylor-error --order 3 --taylor 1.5 --beta "$hi" --degrees --format csv >"$TMP/b" 2>/dev/null
awk -v a="$(csv_value "$TMP/a" 1 10)" -v b="$(csv_value "$TMP/b" 1 10)" 'BEGIN { exit !(a <= 1e-2 && b > 1e-2) }' \
    && ok "the limit $lim° is where the lobe error crosses 1e-2" || notok "limit $lim: $(cat "$TMP/a" "$TMP/b")"
expect_warning "rotmat taylor1 at 1 rad warns" "$A" rotmat --order 4 --method taylor1 --euler 0,1,0
expect_quiet "rotate taylor1.5 at 2°: no warning" rotate --method taylor1.5 --euler 30,2,-45 --degrees --coeffs 0,0,0,0,0,1,0,0,0
expect_quiet "rotate zxzxz at 60°: no warning" rotate --method zxzxz --euler 30,60,-45 --degrees --coeffs 0,0,0,0,0,1,0,0,0
