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
#      reference's and the transfer's noise; the error left at order 1 is the
#      transfer's noise, which the reference must be 10× below (the rule of
#      trusted decisions: tests/cli/test_scene_plan_trust.sh), hence its samples
expect_success "scene-plan constant light" scene-plan --scene bowl --res 4 --light const:1 --budget 0.05 --max-order 3 --vertices 50 --rays 1024 --ref-samples 16384 --quiet --format json
grep -q '"order":1,' "$TMP/out" && ok "constant light: order 1" || notok "constant light: order 1: $(head -c 400 "$TMP/out")"
"$SHLAB" scene-plan --scene sphere-plane --res 2 --light cie-clear:0.5,0.3 --budget 1e-9 --max-order 2 --vertices 20 --rays 64 --ref-samples 64 --quiet --format json >"$TMP/out" 2>"$TMP/err"; rc=$?
[ "$rc" = 1 ] && grep -q '"decision":"undecided","order":null' "$TMP/out" && ok "budget 1e-9 (no reference is 10× below it): exit 1, undecided" || notok "budget 1e-9 (exit $rc)"

# ---- render: EXR and PNG written, error image
expect_success "render" render --scene sphere-plane --res 2 --light cie-clear:0.5,0.3 --rays 64 --order 3 --width 64 --height 48 --out "$TMP/a.exr" --png "$TMP/a.png" --error-png "$TMP/e.png" --ref-samples 256 --quiet --format json
[ -s "$TMP/a.exr" ] && [ -s "$TMP/a.png" ] && [ -s "$TMP/e.png" ] && ok "render files written" || notok "render files written"
head -c 8 "$TMP/a.png" | od -An -c | grep -q 'P   N   G' && ok "PNG signature" || notok "PNG signature"
expect_success "rendered EXR reads back" project --exr "$TMP/a.exr" --order 1 --format json
# ---- the output contract of the scene commands (README "Bad input"): every
#      output file is all or nothing — written beside its target and renamed
#      only once the result is on stdout; an error (here stdout on /dev/full,
#      or an unwritable second file) keeps existing files intact, writes no
#      new one and leaves no temporary behind
no_tmp() { [ -z "$(find "$1" -name '*.tmp.*' 2>/dev/null)" ]; }
mkdir -p "$TMP/k"
R="render --scene sphere-plane --res 2 --light cie-clear:0.5,0.3 --rays 16 --order 2 --width 16 --height 12 --quiet"
for f in a.exr a.png e.exr e.png; do printf 'keep me' >"$TMP/k/$f"; done
"$SHLAB" $R --out "$TMP/k/a.exr" --png "$TMP/k/a.png" --error-out "$TMP/k/e.exr" --error-png "$TMP/k/e.png" --ref-samples 64 >/dev/full 2>"$TMP/err"; rc=$?
[ "$rc" = 2 ] && [ "$(wc -l <"$TMP/err")" = 1 ] && ok "render > /dev/full: exit 2, one line" || notok "render > /dev/full: exit $rc, $(cat "$TMP/err")"
kept=1; for f in a.exr a.png e.exr e.png; do [ "$(cat "$TMP/k/$f")" = "keep me" ] || kept=0; done
[ $kept = 1 ] && ok "render > /dev/full keeps the four existing files" || notok "render > /dev/full changed a file"
no_tmp "$TMP/k" && ok "render > /dev/full leaves no temporary" || notok "temporary left: $(ls "$TMP/k")"
"$SHLAB" $R --out "$TMP/k/new.exr" --png "$TMP/k/new.png" >/dev/full 2>/dev/null
[ ! -e "$TMP/k/new.exr" ] && [ ! -e "$TMP/k/new.png" ] && ok "render > /dev/full writes no new file" || notok "render > /dev/full wrote a file"
expect_usage_error "render with an unwritable PNG (checked before the work)" $R --out "$TMP/k/a.exr" --png "$TMP/k/no/dir/a.png"
[ "$(cat "$TMP/k/a.exr")" = "keep me" ] && no_tmp "$TMP/k" && ok "unwritable PNG: the EXR is not written either" || notok "unwritable PNG: a.exr changed or temporary left"
expect_usage_error "render --png onto --out" $R --out "$TMP/k/a.exr" --png "$TMP/k/a.exr"
expect_usage_error "render --out a directory" $R --out "$TMP/k"
expect_success "render replaces the files on success" $R --out "$TMP/k/a.exr" --png "$TMP/k/a.png"
[ "$(head -c 4 "$TMP/k/a.exr" | od -An -tx1 | tr -d ' ')" = 762f3101 ] && head -c 8 "$TMP/k/a.png" | od -An -c | grep -q 'P   N   G' \
    && no_tmp "$TMP/k" && ok "a.exr and a.png replaced, no temporary" || notok "a.exr/a.png not replaced"
printf 'keep me' >"$TMP/k/c.png"
"$SHLAB" cache --scene sphere-plane --res 2 --light green --order 3 --env-samples 64 --repeat 1 --methods zxzxz --png "$TMP/k/c.png" --width 16 --height 12 --quiet >/dev/full 2>"$TMP/err"; rc=$?
[ "$rc" = 2 ] && [ "$(cat "$TMP/k/c.png")" = "keep me" ] && no_tmp "$TMP/k" && ok "cache > /dev/full keeps its picture" || notok "cache > /dev/full: exit $rc, $(cat "$TMP/err")"
printf 'keep me' >"$TMP/k/s.png"
"$SHLAB" shadow-field --res 2 --light green --order 3 --samples 0 --rays 16 --png "$TMP/k/s.png" --width 16 --height 12 --quiet >/dev/full 2>"$TMP/err"; rc=$?
[ "$rc" = 2 ] && [ "$(cat "$TMP/k/s.png")" = "keep me" ] && no_tmp "$TMP/k" && ok "shadow-field > /dev/full keeps its picture" || notok "shadow-field > /dev/full: exit $rc, $(cat "$TMP/err")"
expect_usage_error "shadow-field picture into a missing directory" shadow-field --res 2 --light green --order 3 --png "$TMP/k/no/s.png"

# ---- bad meshes through every command that reads one (one line, exit 2)
mkdir -p "$TMP/dir.obj"
for c in "transfer" "scene-plan --light const:1 --budget 0.1" "render --light const:1 --out $TMP/k/m.exr" "cache --light const:1"; do
    for f in none.ply junk.xyzzy empty.obj nan.obj fan.obj dir.obj; do
        expect_usage_error "${c%% *} --mesh $f" $c --mesh "$TMP/$f"
    done
done
expect_usage_error "a directory as mesh" transfer --mesh "$TMP/dir.obj"
grep -q "it is a directory" "$TMP/err" && ok "a directory is named as such" || notok "directory mesh: $(cat "$TMP/err")"
[ ! -e "$TMP/k/m.exr" ] && ok "render with a bad mesh writes nothing" || notok "render with a bad mesh wrote m.exr"
# a file name with a newline stays on one line (escaped)
expect_usage_error "mesh name with a newline" transfer --mesh "$TMP/a
b.ply"
expect_usage_error "probe name with a newline" render --scene bowl --probe "$TMP/a
b.exr" --out "$TMP/k/p.exr"

# ---- repeated options are refused (the shared option code)
expect_usage_error "render --order twice" $R --order 3 --out "$TMP/k/r.exr"
expect_usage_error "transfer --rays twice" transfer --scene bowl --rays 16 --rays 32
expect_usage_error "cache --light twice" cache --scene bowl --light green --light const:1
expect_usage_error "shadow-field --png twice" shadow-field --light green --png "$TMP/k/1.png" --png "$TMP/k/2.png"

# ---- render --help names the methods as the parser spells them
"$SHLAB" render --help | grep -q 'taylor1, taylor1.5, taylor2' && ok "render --help: taylor1.5" || notok "render --help spells taylor1.5 otherwise"
expect_success "render --method taylor1.5" $R --euler 0.1,0.2,0.3 --method taylor1.5 --out "$TMP/k/t.exr" --format json
exit 0
