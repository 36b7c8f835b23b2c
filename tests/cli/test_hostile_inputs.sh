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

# ---- memory as a whole before a command starts
expect_refused "bench: the entries of one order together, before any plan" \
    "bench: timing order 1400 \(20 entries at once\) needs [0-9.]+ GB of memory, only [0-9.]+ GB is available" \
    bench --order 1400 --methods zxzxz --mode all --input euler,matrix --kernel scalar,sse2,avx2,avx512
seq 1 1500 | tr '\n' ' ' >"$TMP/c1500.txt"
expect_refused "rotate --order 1: a coefficient file bounded by the order before reading" \
    "coefficient file '.*c1500.txt' has [0-9]+ kB, more than the 4 kB four channels of order 1 take in text" \
    rotate --order 1 --euler 0,0,0 --in "$TMP/c1500.txt"

# ---- one line on exit 2, the right reason
zeros() { awk -v n="$1" 'BEGIN { for (i = 0; i < n; i++) printf "%s0", i ? " " : ""; print "" }'; }
zeros 16384 >"$TMP/c128.txt"
expect_refused "rotate --method z with β ≠ 0 at order 128: the error alone (no note before it)" \
    "method z: rotation is not about z \(beta = 0.2\)" rotate --method z --euler 0.1,0.2,0.3 --in "$TMP/c128.txt"
expect_refused "shadow-field --picture cone: (one line)" "--picture expects an integer, got ''" \
    shadow-field --light const:1 --picture cone:
expect_refused "transfer --check with no closed-form vertex is bad input" \
    "transfer: --check: no vertex of box-open at this --res has a closed form" transfer --scene box-open --res 1 --check
expect_refused "cache --bounce in the closed box: no light, not 'the reference'" \
    "no light reaches the scene: the shading the errors are relative to is 0 at all [0-9]+ vertices" \
    cache --scene box-closed --res 2 --bounce --light const:1 --rays 4 --quiet
grep -q reference "$TMP/err" && notok "the message names no reference ($(cat "$TMP/err"))" || ok "the message names no reference"
perl "$(dirname "$0")/mkexr.pl" 1 4 >"$TMP/w1.exr"
perl "$(dirname "$0")/mkexr.pl" 4 2 >"$TMP/w4.exr"
expect_refused "a 1-pixel-wide RGB environment is too small (not 'need a 1-channel or RGB image')" \
    "w1.exr: a 1×4 environment is too small" render --scene bowl --res 2 --probe "$TMP/w1.exr" --quiet --out "$TMP/r.exr"
expect_refused "a 4×2 probe cannot carry order 8 in a scene command" \
    "a 4×2 image carries orders up to 2 \(2n − 1 pixels across, n down\), not 8" \
    render --scene bowl --res 2 --probe "$TMP/w4.exr" --order 8 --quiet --out "$TMP/r.exr"
expect_success "the same probe carries order 2" render --scene bowl --res 2 --probe "$TMP/w4.exr" --order 2 --rays 16 \
    --width 16 --height 12 --quiet --out "$TMP/r.exr"
# the independent truth of the image: a constant 1 projects to c0 = √(4π)
"$SHLAB" project --order 1 --exr "$TMP/w4.exr" --format csv >"$TMP/out" 2>/dev/null
close "$(csv_value "$TMP/out" 1 "$(head -1 "$TMP/out" | tr ',' '\n' | grep -n '^R$' | cut -d: -f1)")" 3.5449077018110318 1e-7 \
    && ok "mkexr.pl writes what it says (constant 1: c0 = √(4π))" || notok "mkexr.pl image: $(cat "$TMP/out")"

# ---- shadow-field: an absurd run refused before the scene is built
start=$(date +%s)
expect_refused "shadow-field --res 512 refused up front" \
    "shadow-field: --res 512 makes 12582915 vertices; × --rays 4096 that is up to 5.2e\+10 rays, more than the 8.6e\+09" \
    shadow-field --light const:1 --res 512
[ $(( $(date +%s) - start )) -le 3 ] && ok "... within 3 s (nothing built)" || notok "--res 512 took $(( $(date +%s) - start )) s to refuse"

# ---- progress on long runs (stderr, "cmd: done of total what, T s"), none with --quiet
zeros 40401 >"$TMP/c201.txt"
SHLAB_PROGRESS_INTERVAL=0 "$SHLAB" rotate --method ivanic --euler 0.1,0.2,0.3 --in "$TMP/c201.txt" --format json >"$TMP/a" 2>"$TMP/err"; rc=$?
if [ $rc = 0 ] && grep -Eq '^rotate: [0-9]+ of 201 bands of the rotation, [0-9.]+ s$' "$TMP/err" \
    && tail -1 "$TMP/err" | grep -q '^rotate: 201 of 201 bands'; then
    ok "rotate --method ivanic at order 201: progress by bands (SHLAB_PROGRESS_INTERVAL=0), the last line at 201"
else
    notok "rotate progress: rc $rc, $(cat "$TMP/err")"
fi
SHLAB_PROGRESS_INTERVAL=0 "$SHLAB" rotate --method ivanic --euler 0.1,0.2,0.3 --in "$TMP/c201.txt" --format json --quiet >"$TMP/b" 2>"$TMP/err"
[ ! -s "$TMP/err" ] && cmp -s "$TMP/a" "$TMP/b" && ok "rotate --quiet: nothing on stderr, the same result" || notok "rotate --quiet: $(cat "$TMP/err")"

# ---- an option that does not apply is refused (one rule: transfer, render, cache, shadow-field)
B="--scene bowl --res 2 --light const:1 --quiet"
expect_refused "transfer --replications without --check" "transfer: --replications applies only to --check$" transfer --scene bowl --replications 3
expect_refused "render --exposure without --png" "render: --exposure applies only to --png" render $B --out "$TMP/r.exr" --exposure 2
expect_refused "render --error-max without --error-png" "render: --error-max applies only to --error-png$" render $B --out "$TMP/r.exr" --error-max 0.5
expect_refused "render --ref-samples without an error image" "render: --ref-samples applies only to --error-out and --error-png" \
    render $B --out "$TMP/r.exr" --ref-samples 64
expect_refused "render --method without a rotation" "render: --method applies only to a rotation of the lighting" \
    render $B --out "$TMP/r.exr" --method zxzxz
expect_refused "cache --rays without --bounce" "cache: --rays applies only to --bounce" cache $B --rays 16
expect_refused "cache --replications without --reference" "cache: --replications applies only to --reference K$" cache $B --replications 3
expect_refused "cache --width without a picture" "cache: --width applies only to the pictures" cache $B --width 64
expect_refused "cache --view without a picture or phong" "cache: --view applies only to the pictures and --brdf phong" cache $B --view 1,0,0
expect_refused "cache --picture-method without a picture" "cache: --picture-method applies only to --png and --error-png$" \
    cache $B --picture-method zxzxz
expect_refused "cache --beta-lim with exact methods only" "cache: --beta-lim applies only to the Taylor methods" \
    cache $B --methods zxzxz,ivanic --beta-lim 0.2
expect_refused "shadow-field --ref-samples without --reference" "shadow-field: --ref-samples applies only to --reference$" \
    shadow-field --light const:1 --ref-samples 64
expect_refused "shadow-field --picture without --png" "shadow-field: --picture applies only to --png and --error-png$" \
    shadow-field --light const:1 --picture sphere:0
expect_refused "shadow-field --height without a picture" "shadow-field: --height applies only to the pictures" \
    shadow-field --light const:1 --height 64
expect_refused "transfer --compute-normals on a procedural scene" "transfer: --compute-normals applies only to --mesh$" \
    transfer --scene bowl --compute-normals
expect_success "cache --rays with --bounce" cache $B --order 2 --bounce --rays 4 --env-samples 16 --repeat 1 --methods zxzxz

# ---- merge checks every line it passes (types, fields, the band sequence, no
# NUL), refusing a bad one in one line naming the file and the line
for i in 0 1; do "$SHLAB" stability --method zxzxz --lmax 6 --ref-max 2 --shard $i/2 >"$TMP/st$i" 2>/dev/null; done
"$SHLAB" merge "$TMP/st0" "$TMP/st1" >"$TMP/merged" 2>"$TMP/err" && [ ! -s "$TMP/err" ] && ok "the shards merge" || notok "merge: $(cat "$TMP/err")"
"$SHLAB" stability --method zxzxz --lmax 6 --ref-max 2 >"$TMP/whole" 2>/dev/null
cmp -s "$TMP/whole" "$TMP/merged" && ok "... to the unsharded output" || notok "merged output differs"
sed 's/"band":3/"band":5/' "$TMP/st0" >"$TMP/x"
expect_refused "merge: a relabelled band" "merge: .*/x line 3: the row of item 3: band 5, but item 3 is band 3$" merge "$TMP/x" "$TMP/st1"
sed 's/"orth":[-0-9.e]*,"orth_exact":true,"hom"/"orth":"x","orth_exact":true,"hom"/' "$TMP/st1" >"$TMP/x"
expect_refused "merge: \"orth\":\"x\"" "merge: .*/x line 2: the row of item 1: field 'orth' is a string, not a real or null$" \
    merge "$TMP/st0" "$TMP/x"
sed 's/,"hom":[-0-9.e]*//' "$TMP/st1" >"$TMP/x"
expect_refused "merge: a missing field" "line 2: the row of item 1: field 'hom' is missing$" merge "$TMP/st0" "$TMP/x"
sed 's/"broken":false}}/"broken":false,"note":"hi"}}/' "$TMP/st1" >"$TMP/x"
expect_refused "merge: an extra field" "line 2: the row of item 1: unexpected field 'note'$" merge "$TMP/st0" "$TMP/x"
sed 's/"band":3,"orth":[-0-9.e]*,/"band":3,"orth":1,/' "$TMP/st0" >"$TMP/x"
expect_refused "merge: an integer where a real was written" "line 3: the row of item 3: field 'orth' is an integer" merge "$TMP/x" "$TMP/st1"
perl -pe 's/\}\}$/}}\0junk/ if $. == 2' "$TMP/st0" >"$TMP/x"
expect_refused "merge: a NUL byte inside a line" "merge: .*/x line 2: a NUL byte" merge "$TMP/x" "$TMP/st1"
sed 's/{"end":{"rows":[0-9]*,"stopped":false}}/{"end":{}}/' "$TMP/st0" >"$TMP/x"
expect_refused "merge: {\"end\":{}} (was 'counts -1 rows')" "line 5: the end line: field 'rows' is missing$" merge "$TMP/x" "$TMP/st1"
grep -q -- '-1 rows' "$TMP/err" && notok "the message still counts -1 rows" || ok "no '-1 rows'"
sed 's/"lmax":6/"lmax":7/' "$TMP/st0" >"$TMP/x"; sed 's/"lmax":6/"lmax":7/' "$TMP/st1" >"$TMP/y"
expect_refused "merge: parameters edited in every file" "line [0-9]+: the row of item [0-9]+: the sweep has 7 items, its parameters 8 bands" \
    merge "$TMP/x" "$TMP/y"
