#!/bin/sh
# test_scene.sh — the scene commands: transfer, scene-plan, render.
. "$(dirname "$0")/lib.inc"

for c in transfer scene-plan render; do
    if "$SHLAB" $c --help >"$TMP/out" 2>"$TMP/err" && grep -q "^Usage: shlab $c" "$TMP/out"; then ok "$c --help"; else notok "$c --help"; fi
done

# ---- bad meshes: one error line, exit 2, nothing on stdout
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\n' > "$TMP/empty.obj"
printf 'v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$TMP/nan.obj"
printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n' > "$TMP/degenerate.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n' > "$TMP/fan.obj"
printf 'not a mesh at all\n' > "$TMP/junk.xyzzy"
expect_usage_error "missing mesh file" transfer --mesh "$TMP/none.ply"
expect_usage_error "unsupported format" transfer --mesh "$TMP/junk.xyzzy"
expect_usage_error "empty mesh" transfer --mesh "$TMP/empty.obj"
expect_usage_error "NaN vertex" transfer --mesh "$TMP/nan.obj"
expect_usage_error "all triangles degenerate" transfer --mesh "$TMP/degenerate.obj"
expect_usage_error "non-manifold mesh" transfer --mesh "$TMP/fan.obj"
expect_success "non-manifold mesh allowed" transfer --mesh "$TMP/fan.obj" --allow-nonmanifold --rays 16 --format csv
if grep -q 'nonmanifold_edges' "$TMP/out" && [ "$(csv_value "$TMP/out" 1 "$(head -1 "$TMP/out" | tr ',' '\n' | grep -n '^mesh.nonmanifold_edges$' | cut -d: -f1)")" = 1 ]; then
    ok "non-manifold edge reported"; else notok "non-manifold edge reported"; fi

# ---- bad usage
expect_usage_error "no scene" transfer
expect_usage_error "mesh and scene" transfer --mesh "$TMP/fan.obj" --scene bowl
expect_usage_error "unknown scene" transfer --scene teapot
expect_usage_error "rays 0" transfer --scene bowl --rays 0
expect_usage_error "albedo 2" transfer --scene bowl --albedo 2
expect_usage_error "check on a mesh" transfer --mesh "$TMP/fan.obj" --allow-nonmanifold --check
expect_usage_error "closed form shadowed" transfer --scene bowl --closed-form
expect_usage_error "scene-plan without budget" scene-plan --scene bowl --light const:1
expect_usage_error "scene-plan without environment" scene-plan --scene bowl --budget 0.01
expect_usage_error "scene-plan missing probe" scene-plan --scene bowl --probe "$TMP/none.exr" --budget 0.01
expect_usage_error "scene-plan budget 2" scene-plan --scene bowl --light const:1 --budget 2
expect_usage_error "render without --out" render --scene bowl --light const:1
expect_usage_error "render into a missing directory" render --scene bowl --res 4 --light const:1 --rays 16 --out "$TMP/no/dir/x.exr"
[ ! -e "$TMP/no" ] && ok "no output directory created" || notok "no output directory created"

# ---- the closed forms, through the CLI (exit 0 = every vertex within its bound)
for s in sphere-plane bowl box-open; do
    expect_success "transfer --check $s" transfer --scene $s --res 4 --order 3 --rays 256 --replications 8 --check --quiet --format json
    grep -q '"ok":true' "$TMP/out" && ok "$s closed form holds" || notok "$s closed form holds: $(cat "$TMP/out")"
done
expect_success "furnace bowl ρ = 1" transfer --scene bowl --res 4 --order 1 --rays 64 --transfer interreflected --bounce-tol 1e-12 --bounces 1000 --replications 2 --check --quiet --format json
grep -q '"ok":true' "$TMP/out" && ok "furnace holds" || notok "furnace holds: $(cat "$TMP/out")"
expect_success "closed box" transfer --scene box-closed --res 4 --order 1 --rays 64 --transfer interreflected --bounces 1 --quiet --format json
grep -Eq '"escaped_fraction":0(\.0)?[,}]' "$TMP/out" && ok "closed box: no ray escapes" || notok "closed box: no ray escapes: $(cat "$TMP/out")"

# ---- scene-plan: a constant light on the bowl is shaded exactly at order 1
#      (t_0 carries all of a constant), so order 1 meets any budget above the
#      reference's and the transfer's noise
expect_success "scene-plan constant light" scene-plan --scene bowl --res 4 --light const:1 --budget 0.05 --max-order 3 --vertices 50 --rays 1024 --ref-samples 1024 --quiet --format json
grep -q '"order":1,' "$TMP/out" && ok "constant light: order 1" || notok "constant light: order 1: $(head -c 400 "$TMP/out")"
"$SHLAB" scene-plan --scene sphere-plane --res 2 --light cie-clear:0.5,0.3 --budget 1e-9 --max-order 2 --vertices 20 --rays 64 --ref-samples 64 --quiet --format json >"$TMP/out" 2>"$TMP/err"; rc=$?
[ "$rc" = 1 ] && grep -q '"order":null' "$TMP/out" && ok "impossible budget: exit 1, order null" || notok "impossible budget (exit $rc)"

# ---- render: EXR and PNG written, error image
expect_success "render" render --scene sphere-plane --res 2 --light cie-clear:0.5,0.3 --rays 64 --order 3 --width 64 --height 48 --out "$TMP/a.exr" --png "$TMP/a.png" --error-png "$TMP/e.png" --ref-samples 256 --quiet --format json
[ -s "$TMP/a.exr" ] && [ -s "$TMP/a.png" ] && [ -s "$TMP/e.png" ] && ok "render files written" || notok "render files written"
head -c 8 "$TMP/a.png" | od -An -c | grep -q 'P   N   G' && ok "PNG signature" || notok "PNG signature"
expect_success "rendered EXR reads back" project --exr "$TMP/a.exr" --order 1 --format json
exit 0
