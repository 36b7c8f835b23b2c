#!/bin/sh
# test_cache.sh — the radiance cache and shadow-field commands.
. "$(dirname "$0")/lib.inc"

for c in cache shadow-field; do
    if "$SHLAB" $c --help >"$TMP/out" 2>"$TMP/err" && grep -q "^Usage: shlab $c" "$TMP/out"; then ok "$c --help"; else notok "$c --help"; fi
done

# ---- bad usage: one error line, exit 2, nothing on stdout
S="--scene sphere-plane --res 2"
expect_usage_error "cache without environment" cache $S
expect_usage_error "cache allowed error 0" cache $S --light green --allowed-error 0
expect_usage_error "cache unknown method" cache $S --light green --methods zxzxz,spin
expect_usage_error "cache z method" cache $S --light green --methods z
expect_usage_error "cache method twice" cache $S --light green --methods zxzxz,zxzxz
expect_usage_error "cache phong exponent 0" cache $S --light green --brdf phong:0
expect_usage_error "cache unknown brdf" cache $S --light green --brdf ward
expect_usage_error "cache reference with bounce" cache $S --light green --bounce --reference 10
expect_usage_error "cache picture method not listed" cache $S --light green --methods zxzxz --picture-method taylor1 --png "$TMP/x.png"
expect_usage_error "cache order 40" cache $S --light green --order 40
expect_usage_error "cache rmin above rmax" cache $S --light green --rmin 0.5 --rmax 0.1
expect_usage_error "cache missing probe" cache $S --probe "$TMP/none.exr"
expect_usage_error "cache png into a missing directory" cache $S --light green --env-samples 64 --repeat 1 --png "$TMP/no/x.png" --quiet
[ ! -e "$TMP/no" ] && ok "no output directory created" || notok "no output directory created"
expect_usage_error "shadow-field on the bowl" shadow-field --scene bowl --light green
expect_usage_error "shadow-field on a mesh" shadow-field --mesh "$TMP/none.ply" --light green
expect_usage_error "shadow-field samples 1" shadow-field --light green --samples 0,1
expect_usage_error "shadow-field field inside the sphere" shadow-field --light green --field-distance 0.3
expect_usage_error "shadow-field exact with samples" shadow-field --light green --picture exact:5 --png "$TMP/x.png"
expect_usage_error "shadow-field order 17" shadow-field --light green --order 17

# ---- a record at every vertex (a tiny allowed error): the cache is the
#      direct computation, for every rotation method, exactly
expect_success "cache, a record everywhere" cache $S --light green --order 4 --allowed-error 1e-9 --env-samples 64 --repeat 1 --quiet --format json
n=$(grep -o '"rel_l2":[0-9.e+-]*' "$TMP/out" | grep -c '"rel_l2":0\(\.0\)\?$')
[ "$n" = 6 ] && ok "every method: rel_l2 = 0" || notok "every method: rel_l2 = 0 ($n of 6): $(head -c 600 "$TMP/out")"
grep -q '"records":195,' "$TMP/out" && grep -q '"vertices":195,' "$TMP/out" && ok "records = vertices" || notok "records = vertices"

# ---- a cache with real reuse: the exact methods agree, Taylor differs a little,
#      pictures written
expect_success "cache" cache $S --light green --order 5 --allowed-error 0.5 --env-samples 128 --repeat 2 --methods ignore,taylor1.5,zxzxz,ivanic --png "$TMP/c.png" --direct-png "$TMP/d.png" --error-png "$TMP/e.png" --width 64 --height 48 --quiet --format csv
col() { head -1 "$TMP/out" | tr ',' '\n' | grep -n "^$1\$" | cut -d: -f1; }
iv=$(awk -F, -v c="$(col rot_rel_l2)" -v m="$(col method)" '$m == "ivanic" { print $c }' "$TMP/out")
t15=$(awk -F, -v c="$(col rot_rel_l2)" -v m="$(col method)" '$m == "taylor1.5" { print $c }' "$TMP/out")
awk -v a="$iv" 'BEGIN { exit !(a < 1e-12) }' && ok "ivanic = zxzxz ($iv)" || notok "ivanic = zxzxz ($iv)"
awk -v a="$t15" 'BEGIN { exit !(a > 0 && a < 0.5) }' && ok "taylor1.5 differs a little ($t15)" || notok "taylor1.5 differs a little ($t15)"
[ -s "$TMP/c.png" ] && [ -s "$TMP/d.png" ] && [ -s "$TMP/e.png" ] && ok "cache pictures written" || notok "cache pictures written"
expect_success "cache phong with bounce and noise" cache $S --light green --order 3 --brdf phong:7 --bounce --noise --env-samples 64 --rays 16 --repeat 1 --methods zxzxz --quiet --format json
grep -q '"brdf":"phong:7"' "$TMP/out" && grep -q '"noise_l2":' "$TMP/out" && ok "phong, bounce, noise reported" || notok "phong, bounce, noise reported"
expect_success "cache with the reference" cache $S --light green --order 3 --env-samples 64 --repeat 1 --methods zxzxz --reference 20 --ref-samples 256 --quiet --format json
grep -q '"reference":{"vertices":20,' "$TMP/out" && grep -q '"ref_rel_l2":' "$TMP/out" && ok "reference compared" || notok "reference compared"

# ---- shadow fields
expect_success "shadow-field" shadow-field --res 2 --light green --order 3 --samples 0,3 --rays 64 --bins 3 --png "$TMP/s.png" --ray-png "$TMP/r.png" --error-png "$TMP/se.png" --width 64 --height 48 --quiet --format json
grep -q '"receivers":81,' "$TMP/out" && ok "81 plane receivers" || notok "81 plane receivers"
[ "$(grep -o '"scaling":' "$TMP/out" | wc -l)" = 5 ] && ok "exact + 2 × (cone, sphere) fields" || notok "fields: $(head -c 400 "$TMP/out")"
[ -s "$TMP/s.png" ] && [ -s "$TMP/r.png" ] && [ -s "$TMP/se.png" ] && ok "shadow-field pictures written" || notok "shadow-field pictures written"
exit 0
