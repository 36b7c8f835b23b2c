#!/bin/sh
# test_scene_plan_trust.sh — scene-plan's trusted decisions (docs/CONVENTIONS.md
# "Trusted decisions"): a decision stands only when the reference's own error
# is ≤ min(budget, rel_l2 at the order)/10 over the comparisons it rests on,
# else it is "undecided"; the reference is refined first, within --refine.
# The truth is the rule applied here, by awk, to the numbers the command itself
# prints (the errors at every order and the reference's error).
. "$(dirname "$0")/lib.inc"

# box-open under Green's light: little sky is seen, visibility carries the
# reference's variance; a light spec without a comma keeps the CSV simple
P="scene-plan --scene box-open --res 4 --light green --max-order 4 --vertices 40 --rays 256 --ref-samples 1024 --quiet"

# rule FILE: the printed decisions of a CSV result against the rule; prints
# the disagreements, exit 1 if any
rule() {
    awk -F, '
    /^scene\.scene,/ { blk++; for (i = 1; i <= NF; i++) col[blk, $i] = i; next }
    NF == 0 { next }
    blk == 1 { k = $col[1, "order"] + 0; err[k] = $col[1, "rel_l2"] + 0; if (k > N) N = k; r = $col[1, "reference.ref_l2"] + 0 }
    blk == 2 { nb++; E[nb] = $col[2, "budget"] + 0; dec[nb] = $col[2, "decision"]; ord[nb] = $col[2, "order"] }
    END {
        if (!N || !nb) { print "no orders or budgets printed"; exit 1 }
        bad = 0
        for (b = 1; b <= nb; b++) {
            n = 0
            for (k = 1; k <= N && !n; k++) if (err[k] <= E[b]) n = k
            need = E[b] / 10
            last = n ? n : N
            for (k = 1; k <= last; k++) if (err[k] / 10 < need) need = err[k] / 10
            want = r <= need ? "decided" : "undecided"
            wo = want == "decided" && n ? n : ""
            if (dec[b] != want || ord[b] != wo) {
                printf "budget %g: printed %s %s, the rule gives %s %s (ref_l2 %g, needed %g)\n", E[b], dec[b], ord[b], want, wo, r, need
                bad = 1
            }
        }
        exit bad
    }' "$1"
}
# field FILE BLOCK ROW NAME: the value of column NAME in data row ROW of block BLOCK
field() {
    awk -F, -v B="$2" -v R="$3" -v name="$4" '
    /^scene\.scene,/ { blk++; row = 0; for (i = 1; i <= NF; i++) if ($i == name) c = i; next }
    NF == 0 { next }
    blk == B && ++row == R { print $c; exit }' "$1"
}

# stable FILE: the CSV without its timings (reference.seconds, reference.rays_per_s)
stable() {
    awk -F, '
    /^scene\.scene,/ { for (i = 1; i <= NF; i++) skip[i] = $i == "reference.seconds" || $i == "reference.rays_per_s" }
    { s = ""; for (i = 1; i <= NF; i++) if (!skip[i]) s = s $i ","; print s }' "$1"
}

# ---- no refinement: a budget far below the reference's error is undecided,
#      one far above it is decided with an order
"$SHLAB" $P --budget 0.9,0.001 --refine 1 --format csv >"$TMP/out" 2>"$TMP/err"; rc=$?
[ "$rc" = 1 ] && ok "an undecided budget: exit 1" || notok "an undecided budget: exit $rc ($(head -c 300 "$TMP/err"))"
r0=$(field "$TMP/out" 1 1 reference.ref_l2)
awk -v r="$r0" 'BEGIN { exit !(r > 0.0001 && r < 0.09) }' && ok "the reference's error ($r0) lies between the two budgets' needs" \
    || notok "reference error $r0 not between 1e-4 and 0.09: the cases below test nothing"
[ "$(field "$TMP/out" 2 2 decision)" = undecided ] && [ -z "$(field "$TMP/out" 2 2 order)" ] \
    && ok "budget 0.001: undecided, no order" || notok "budget 0.001: $(tail -1 "$TMP/out")"
o=$(field "$TMP/out" 2 1 order)
[ "$(field "$TMP/out" 2 1 decision)" = decided ] && [ -n "$o" ] && ok "budget 0.9: decided, order $o" || notok "budget 0.9: $(sed -n '/budget/,$p' "$TMP/out")"
rule "$TMP/out" >"$TMP/why" && ok "the printed decisions follow the rule on the printed numbers" || notok "rule: $(cat "$TMP/why")"
[ "$(field "$TMP/out" 2 2 replications_needed)" -gt 4 ] 2>/dev/null && ok "undecided: the replications it would need are printed" \
    || notok "replications_needed: $(field "$TMP/out" 2 2 replications_needed)"
[ "$(grep -c 'order undecided' "$TMP/err")" = 1 ] && ok "one stderr line says undecided" || notok "stderr: $(cat "$TMP/err")"
"$SHLAB" $P --budget 0.9,0.001 --refine 1 --format table >"$TMP/tab" 2>/dev/null
grep -Eq '^0\.001[[:space:]]+undecided' "$TMP/tab" && ok "the table says undecided" || notok "table: $(tail -3 "$TMP/tab")"

# ---- refinement: a budget 6× the reference's error asks for a reference at
#      most 0.6× as large; refused without refinement, decided with it, the
#      reference's error falling as 1/√replications
E=$(awk -v r="$r0" 'BEGIN { printf "%.6g", 6 * r }')
"$SHLAB" $P --budget "$E" --refine 1 --format csv >"$TMP/out1" 2>/dev/null
[ "$(field "$TMP/out1" 2 1 decision)" = undecided ] && ok "budget $E without refinement: undecided" || notok "budget $E, --refine 1: $(tail -1 "$TMP/out1")"
"$SHLAB" $P --budget "$E" --format csv >"$TMP/out2" 2>/dev/null
R=$(field "$TMP/out2" 1 1 reference.replications_used)
r=$(field "$TMP/out2" 1 1 reference.ref_l2)
[ "$(field "$TMP/out2" 2 1 decision)" = decided ] && ok "budget $E refined ($R replications): decided" || notok "budget $E refined: $(tail -1 "$TMP/out2")"
awk -v R="$R" 'BEGIN { exit !(R > 4 && R <= 64) }' && ok "refined within the cap (4 < $R <= 16 × 4)" || notok "replications used: $R"
rule "$TMP/out2" >"$TMP/why" && ok "refined: the decision follows the rule on the printed numbers" || notok "rule: $(cat "$TMP/why")"
# 1/√R, within the spread of an error estimated from 4 replications (±30 %)
awk -v a="$r0" -v b="$r" -v R="$R" 'BEGIN { q = (a / b) / sqrt(R / 4); exit !(q > 1 / 1.3 && q < 1.3) }' \
    && ok "ref_l2 $r0 -> $r: as 1/sqrt(replications)" || notok "ref_l2 $r0 -> $r with $R replications is not about 1/sqrt(R/4)"
"$SHLAB" $P --budget "$E" --format csv >"$TMP/out3" 2>/dev/null
stable "$TMP/out2" >"$TMP/s2"
stable "$TMP/out3" >"$TMP/s3"
[ -s "$TMP/s2" ] && cmp -s "$TMP/s2" "$TMP/s3" && ok "the refinement is deterministic" || notok "two runs differ: $(diff "$TMP/s2" "$TMP/s3" | head -4)"

# ---- the rotation study: each Taylor method's largest β is decided or
#      undecided per the rule, and says which
"$SHLAB" $P --budget 0.9 --max-beta 20 --beta-step 10 --degrees --format json >"$TMP/rot" 2>"$TMP/err"; rc=$?
grep -Eq '"taylor1":\{"decision":"(decided|undecided)","max_beta"' "$TMP/rot" && ok "rotation: each method's largest β carries its decision" \
    || notok "rotation (exit $rc): $(head -c 300 "$TMP/rot")"
exit 0
