#!/bin/sh
# CLI contract of `shlab scale`, `scale-interp` and `scale-scene` (Wang et al. 2006).
. tests/cli/lib.inc

# json_num FILE KEY : the number after "KEY": in a one-line JSON file
json_num() { sed -n "s/.*\"$2\":\([-0-9.eE+]*\).*/\1/p" "$1"; }
# lt A B : true if A < B numerically
lt() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 < b + 0) }'; }

expect_success "scale --help" scale --help
expect_success "scale-interp --help" scale-interp --help
expect_success "scale-scene --help" scale-scene --help
"$SHLAB" scale --help | grep -q "US patent 7,663,623" && ok "scale --help names the patent" || notok "scale --help: no patent note"

expect_usage_error "scale no order" scale --family linear --k 2
expect_usage_error "scale no family" scale --order 3 --k 2
expect_usage_error "scale no k" scale --order 3 --family linear
expect_usage_error "scale bad family" scale --order 3 --family zoom --k 2
expect_usage_error "scale linear k 0" scale --order 3 --family linear --k 0
expect_usage_error "scale linear k negative" scale --order 3 --family linear --k -2
expect_usage_error "scale cone k huge" scale --order 3 --family cone --k 1e9
expect_usage_error "scale midrange k 1" scale --order 3 --family midrange --k 1
expect_usage_error "scale midrange k -1.2" scale --order 3 --family midrange --k -1.2
expect_usage_error "scale NaN k" scale --order 3 --family linear --k nan
expect_usage_error "scale cone-angle on linear" scale --order 3 --family linear --k 2 --cone-angle 0.5
expect_usage_error "scale cone-angle 180 deg" scale --order 3 --family cone --k 2 --cone-angle 180 --degrees
expect_usage_error "scale order too large" scale --order 40 --family linear --k 2
expect_usage_error "scale --verify order 9" scale --order 9 --family linear --k 2 --verify
expect_usage_error "scale unknown option" scale --order 3 --family linear --k 2 --bogus
expect_usage_error "scale k twice" scale --order 3 --family linear --k 2 --k 3

# k = 1 is the identity: N² non-zeros, and the pattern bound N(2N²+1)/3
expect_success "scale linear k=1" scale --order 4 --family linear --k 1 --energy --format json
[ "$(json_num "$TMP/out" nonzeros)" = 16 ] && ok "k=1: 16 non-zeros (identity)" || notok "k=1 non-zeros $(json_num "$TMP/out" nonzeros)"
[ "$(json_num "$TMP/out" pattern_bound)" = 44 ] && ok "pattern bound 44 at order 4 (the paper's number)" || notok "pattern bound"
# plain scaling keeps constants: column 0 = e_0, so N−1 fewer than the bound
expect_success "scale linear k=2" scale --order 4 --family linear --k 2 --format json
[ "$(json_num "$TMP/out" nonzeros)" = 41 ] && ok "linear k=2 plain: 41 = 44 − 3 non-zeros" || notok "linear k=2 non-zeros $(json_num "$TMP/out" nonzeros)"
grep -q '"convention":"cs"' "$TMP/out" && grep -q '"family":"linear"' "$TMP/out" && ok "scale JSON tags" || notok "scale JSON tags"
# independent computation
for fam in "linear --k 2.5" "cone --k 0.4 --cone-angle 30 --degrees" "midrange --k -0.8 --energy"; do
    # shellcheck disable=SC2086
    expect_success "scale --verify $fam" scale --order 5 --family $fam --verify --convention nocs --format json
    d=$(json_num "$TMP/out" verify_max_diff)
    lt "$d" 1e-10 && ok "verify $fam: $d <= 1e-10" || notok "verify $fam: $d"
done
# the same matrix in both conventions
"$SHLAB" scale --order 4 --family cone --k 1.7 --format json | sed 's/"convention":"cs"//' >"$TMP/a"
"$SHLAB" scale --order 4 --family cone --k 1.7 --convention nocs --format json | sed 's/"convention":"nocs"//' >"$TMP/b"
cmp -s "$TMP/a" "$TMP/b" && ok "M independent of the convention" || notok "M differs between cs and nocs"
grep -qi nan "$TMP/a" && notok "NaN printed" || ok "no NaN in output"

# interpolation
expect_usage_error "scale-interp no samples" scale-interp --order 4 --family cone --spacing geometric --kmin 0.5 --kmax 2
expect_usage_error "scale-interp geometric kmin<0" scale-interp --order 4 --family midrange --samples 10 --spacing geometric --kmin -0.5 --kmax 0.5
expect_usage_error "scale-interp kmin>kmax" scale-interp --order 4 --family cone --samples 10 --spacing uniform --kmin 2 --kmax 1
expect_usage_error "scale-interp cubic 2 samples" scale-interp --order 4 --family cone --samples 2 --spacing uniform --kmin 0.5 --kmax 2 --interp cubic
expect_usage_error "scale-interp bad interp" scale-interp --order 4 --family cone --samples 10 --spacing uniform --kmin 0.5 --kmax 2 --interp quintic
expect_usage_error "scale-interp k outside family" scale-interp --order 4 --family midrange --samples 10 --spacing uniform --kmin -0.5 --kmax 1.5
expect_success "scale-interp 10" scale-interp --order 4 --family cone --samples 10 --spacing geometric --kmin 0.5 --kmax 2 --format json
e10=$(json_num "$TMP/out" max_error)
expect_success "scale-interp 40" scale-interp --order 4 --family cone --samples 40 --spacing geometric --kmin 0.5 --kmax 2 --format json
e40=$(json_num "$TMP/out" max_error)
lt "$e40" "$e10" && ok "40 samples ($e40) beat 10 ($e10)" || notok "interp 40 $e40 vs 10 $e10"
expect_success "scale-interp 40 --quiet" scale-interp --order 4 --family cone --samples 40 --spacing geometric --kmin 0.5 --kmax 2 --format json --quiet
[ ! -s "$TMP/err" ] && [ "$(json_num "$TMP/out" max_error)" = "$e40" ] && ok "scale-interp --quiet: silent, same result" || notok "scale-interp --quiet: $(head -c 200 "$TMP/err")"
expect_success "scale-interp uniform midrange cubic" scale-interp --order 3 --family midrange --samples 21 --spacing uniform --kmin -0.8 --kmax 0.8 --interp cubic --energy

# scenes
expect_usage_error "scale-scene no scene" scale-scene --order 4 --k 2
expect_usage_error "scale-scene bad scene" scale-scene --scene box --order 4 --k 2
expect_usage_error "scale-scene inside sphere" scale-scene --scene sphere --order 4 --k 0.3 --size 0.5
expect_usage_error "scale-scene midrange family linear" scale-scene --scene midrange --order 4 --k 0.5 --family linear
expect_usage_error "scale-scene sphere family midrange" scale-scene --scene sphere --order 4 --k 2 --family midrange
expect_usage_error "scale-scene missing probe" scale-scene --scene midrange --order 4 --k 0.5 --probe "$TMP/none.exr"
expect_usage_error "scale-scene light on sphere" scale-scene --scene sphere --order 4 --k 2 --light green
expect_usage_error "scale-scene order 17" scale-scene --scene sphere --order 17 --k 2
expect_success "scale-scene cone" scale-scene --scene cone --order 4 --k 0.8,1.5 --format csv
# header: scene,order,convention,method,size,occluder_angle,wobble,cone_family_angle,unit,k,family,energy,err_scaled,err_geom,err_trunc
bad=$(awk -F, 'NR > 1 && $11 == "cone" && $12 == "false" && $14 + 0 > 1e-12 { print $10, $14 }' "$TMP/out")
nrows=$(awk -F, 'NR > 1 && $11 == "cone"' "$TMP/out" | wc -l)
[ -z "$bad" ] && [ "$nrows" = 4 ] && ok "cone family is exact geometry on the cone occluder" || notok "cone geometry error: $bad ($nrows rows)"
expect_success "scale-scene midrange" scale-scene --scene midrange --order 4 --k -0.6,0.6 --nodes 100 --format csv
# header: scene,order,convention,method,environment,nodes,dir_x,dir_y,dir_z,rotation_method,k,family,energy,err_scaled,err_geom,err_trunc
head -1 "$TMP/out" | grep -q '^scene,order,convention,method,environment,nodes,dir_x,dir_y,dir_z,rotation_method,k,family,energy,err_scaled,err_geom,err_trunc$' \
    && ok "midrange CSV columns" || notok "midrange CSV header: $(head -1 "$TMP/out")"
bad=$(awk -F, 'NR > 1 && $13 == "false" && $15 + 0 > 1e-12 { print $11, $15 }' "$TMP/out")
nplain=$(awk -F, 'NR > 1 && $13 == "false"' "$TMP/out" | wc -l)
[ -z "$bad" ] && [ "$nplain" = 2 ] && ok "midrange family is exact geometry for plain scaling" || notok "midrange plain geometry error: $bad"
awk -F, 'NR > 1 && ($7 != 0 || $8 != 0 || $9 != 1 || $10 != "none") { bad = 1 } END { exit bad }' "$TMP/out" \
    && ok "midrange default direction +z, no rotation" || notok "midrange default direction"
cp "$TMP/out" "$TMP/zplus"

# displacement in any direction: rotate to the axis, scale, rotate back
expect_usage_error "scale-scene --dir zero" scale-scene --scene midrange --order 4 --k 0.5 --dir 0,0,0
expect_usage_error "scale-scene --dir two numbers" scale-scene --scene midrange --order 4 --k 0.5 --dir 1,2
expect_usage_error "scale-scene --dir NaN" scale-scene --scene midrange --order 4 --k 0.5 --dir nan,0,1
expect_usage_error "scale-scene --dir on sphere" scale-scene --scene sphere --order 4 --k 2 --dir 1,0,0
expect_usage_error "scale-scene --rotation-method on cone" scale-scene --scene cone --order 4 --k 2 --rotation-method blanco
expect_usage_error "scale-scene --rotation-method taylor1.5" scale-scene --scene midrange --order 4 --k 0.5 --dir 1,0,0 --rotation-method taylor1.5
expect_usage_error "scale-scene --rotation-method z" scale-scene --scene midrange --order 4 --k 0.5 --dir 1,0,0 --rotation-method z
expect_usage_error "scale-scene --rotation-method bogus" scale-scene --scene midrange --order 4 --k 0.5 --dir 1,0,0 --rotation-method spin
# k along −z is −k along +z (same errors as the +z run above, in reverse k order)
expect_success "scale-scene midrange --dir 0,0,-1" scale-scene --scene midrange --order 4 --k 0.6,-0.6 --nodes 100 --dir 0,0,-1 --format csv
paste -d, "$TMP/zplus" "$TMP/out" | awk -F, 'NR > 1 { for (c = 14; c <= 16; c++) { d = $c - $(c + 16); if (d < 0) d = -d; if (d > 1e-12 * ($c + 1e-3)) bad = 1 } } END { exit bad }' \
    && awk -F, 'NR > 1 && $10 != "zxzxz" { bad = 1 } END { exit bad }' "$TMP/out" \
    && ok "--dir 0,0,-1 with k = ±0.6 gives the +z errors of k = ∓0.6" || notok "-z vs +z: $(cat "$TMP/out")"
# a tilted axis: plain mid-range scaling is still exact geometry (err_geom is computed about the axis without SH rotations)
for m in zxzxz blanco ivanic; do
    expect_success "scale-scene midrange --dir 1,-2,0.5 ($m)" scale-scene --scene midrange --order 5 --k -0.7,0.8 --nodes 100 --dir 1,-2,0.5 --rotation-method $m --format json
    ng=$(grep -o '"energy":false,"err_scaled":[-0-9.eE+]*,"err_geom":[-0-9.eE+]*' "$TMP/out" | sed 's/.*"err_geom"://' | awk '$1 + 0 < 1e-12' | wc -l)
    [ "$ng" = 2 ] && ok "tilted axis ($m): plain err_geom < 1e-12" || notok "tilted axis ($m): $(cat "$TMP/out")"
done
grep -q '"rotation_method":"ivanic"' "$TMP/out" && grep -q '"dir_y":-0.8728715609439' "$TMP/out" && ok "tilted JSON tags (unit dir, method)" || notok "tilted JSON tags"
