#!/bin/sh
# test_shards.sh — sweeps run as shards (--shard I/N) and joined by
# `shlab merge` give the unsharded output byte for byte: with GNU parallel
# (two processes, as CI and the README run it), in a shell loop, under the
# Slurm array script with its environment simulated; and merge refuses
# shard sets that do not make one sweep.
. "$(dirname "$0")/lib.inc"

STAB="stability --method zxzxz --lmax 24 --ref-max 4"

# --- GNU parallel, two shards, against the unsharded run -----------------------
if command -v parallel >/dev/null 2>&1; then
    "$SHLAB" $STAB --format csv > "$TMP/whole.csv" 2>/dev/null
    # shellcheck disable=SC2086
    parallel "$SHLAB" $STAB --format csv --shard {}/2 '>' "$TMP/par{}.jsonl" ::: 0 1 2>/dev/null
    "$SHLAB" merge "$TMP/par0.jsonl" "$TMP/par1.jsonl" > "$TMP/merged.csv" 2>"$TMP/err"
    if [ -s "$TMP/whole.csv" ] && cmp -s "$TMP/whole.csv" "$TMP/merged.csv"; then
        ok "parallel: 2 shards of stability merge to the unsharded csv"
    else
        notok "parallel: merged stability differs from the unsharded run ($(head -c 200 "$TMP/err"))"
    fi
else
    echo "SKIP test_shards.sh: GNU parallel not installed (Debian package parallel); the shell-loop shards below still run"
fi

# --- every format, 3 shards in a shell loop, files given in any order ---------
for f in csv json table; do
    "$SHLAB" $STAB --format $f > "$TMP/whole" 2>/dev/null
    for i in 0 1 2; do "$SHLAB" $STAB --format $f --shard $i/3 > "$TMP/s$i" 2>/dev/null; done
    "$SHLAB" merge "$TMP/s2" "$TMP/s0" "$TMP/s1" > "$TMP/merged" 2>/dev/null
    cmp -s "$TMP/whole" "$TMP/merged" && ok "stability --format $f: 3 shards merge byte for byte" \
        || notok "stability --format $f: merge differs"
done
# merge --format overrides the sweep's format
"$SHLAB" $STAB --format json > "$TMP/whole" 2>/dev/null
"$SHLAB" merge --format json "$TMP/s0" "$TMP/s1" "$TMP/s2" > "$TMP/merged" 2>/dev/null
cmp -s "$TMP/whole" "$TMP/merged" && ok "merge --format json of table shards" || notok "merge --format json differs"

# the shards split the items: serpentine, every band exactly once, shares within one
n0=$(grep -c '"item"' "$TMP/s0"); n1=$(grep -c '"item"' "$TMP/s1"); n2=$(grep -c '"item"' "$TMP/s2")
bands=$(cat "$TMP/s0" "$TMP/s1" "$TMP/s2" | sed -n 's/^{"item":\([0-9]*\),.*/\1/p' | sort -n | tr '\n' ' ')
want=$(seq 0 24 | tr '\n' ' ')
[ "$bands" = "$want" ] && [ $((n0 + n1 + n2)) = 25 ] && [ "$n0" -le 9 ] && [ "$n1" -le 9 ] && [ "$n2" -le 9 ] \
    && ok "3 shards hold bands 0..24 once each ($n0, $n1, $n2)" || notok "shard items: $bands ($n0 $n1 $n2)"
# shard 1 of 2 owns 1 2 5 6 9 ... (item j to r = j mod 4 if r < 2, else 3 - r)
"$SHLAB" $STAB --shard 1/2 > "$TMP/s" 2>/dev/null
got=$(sed -n 's/^{"item":\([0-9]*\),.*/\1/p' "$TMP/s" | head -6 | tr '\n' ' ')
[ "$got" = "1 2 5 6 9 10 " ] && ok "shard 1/2 owns 1 2 5 6 9 10 ..." || notok "shard 1/2 owns $got"

# a band's row does not depend on the other bands computed (probes seeded by the band)
"$SHLAB" stability --method blanco --lmax 12 --ref-max 4 --format csv > "$TMP/a" 2>/dev/null
"$SHLAB" stability --method blanco --bands 3,12 --ref-max 4 --format csv > "$TMP/b" 2>/dev/null
ra=$(awk -F, '$1 == "blanco" && $6 == 12' "$TMP/a"); rb=$(awk -F, '$1 == "blanco" && $6 == 12' "$TMP/b")
[ -n "$ra" ] && [ "$ra" = "$rb" ] && ok "band 12 alone = band 12 of 0..12" || notok "band 12: '$ra' vs '$rb'"

# --bands and a sweep that stops (--stop-above): rows after the first stop are dropped
SB="stability --method ivanic --bands 2,5,9,14,16,18,20,22,25,30 --ref-max -1 --stop-above 3e-15 --format csv"
"$SHLAB" $SB > "$TMP/whole" 2>/dev/null
for i in 0 1 2; do "$SHLAB" $SB --shard $i/3 > "$TMP/s$i" 2>/dev/null; done
"$SHLAB" merge "$TMP/s0" "$TMP/s1" "$TMP/s2" > "$TMP/merged" 2>"$TMP/err"
last=$(tail -1 "$TMP/whole" | cut -d, -f6)
[ -n "$last" ] && [ "$last" -lt 30 ] && cmp -s "$TMP/whole" "$TMP/merged" \
    && ok "stopped sweep (--stop-above, stops at band $last) merges to the unsharded rows" \
    || notok "stopped sweep: last band '$last', $(head -c 200 "$TMP/err")"

# taylor-error over an angle grid
TE="taylor-error --order 6 --taylor 1.5 --beta-max 30 --steps 9 --degrees --format csv"
"$SHLAB" $TE > "$TMP/whole" 2>/dev/null
for i in 0 1 2 3; do "$SHLAB" $TE --shard $i/4 > "$TMP/t$i" 2>/dev/null; done
"$SHLAB" merge "$TMP/t3" "$TMP/t1" "$TMP/t0" "$TMP/t2" > "$TMP/merged" 2>/dev/null
[ -s "$TMP/whole" ] && cmp -s "$TMP/whole" "$TMP/merged" && ok "taylor-error: 4 shards merge byte for byte" \
    || notok "taylor-error merge differs"
# more shards than items: the empty shards still make a complete set
for i in 0 1 2 3 4 5 6 7 8 9 10 11; do "$SHLAB" $TE --shard $i/12 > "$TMP/u$i" 2>/dev/null; done
"$SHLAB" merge "$TMP"/u* > "$TMP/merged" 2>/dev/null
cmp -s "$TMP/whole" "$TMP/merged" && ok "12 shards of 10 items (two empty) merge" || notok "12 shards merge differs"

# scale-interp over its dense k grid (the sampled table in every shard)
SI="scale-interp --order 5 --family midrange --samples 10 --spacing uniform --kmin -0.5 --kmax 0.6 --dense 33 --interp cubic --format json"
"$SHLAB" $SI > "$TMP/si" 2>/dev/null
for i in 0 1; do "$SHLAB" $SI --shard $i/2 > "$TMP/k$i" 2>/dev/null; done
"$SHLAB" merge "$TMP/k1" "$TMP/k0" > "$TMP/merged" 2>/dev/null
[ -s "$TMP/si" ] && cmp -s "$TMP/si" "$TMP/merged" && ok "scale-interp: 2 shards merge byte for byte" \
    || notok "scale-interp merge differs"

# plan over its β grid: the errors merge exactly; the methods are timed by
# whoever prints the result, so the timing columns (and the ranking by time) differ
PL0="plan --order 5 --max-beta 12 --degrees --format csv --quiet"
PL="$PL0 --tolerance 1e-3"
"$SHLAB" $PL > "$TMP/pl" 2>/dev/null
for i in 0 1 2; do "$SHLAB" $PL --shard $i/3 > "$TMP/p$i" 2>/dev/null; done
"$SHLAB" merge "$TMP/p0" "$TMP/p1" "$TMP/p2" > "$TMP/merged" 2>/dev/null
# candidate columns method, exact, ok, max_error, worst_beta, mults (15-17, 19-21)
cut -d, -f15-17,19-21 "$TMP/pl" | sort > "$TMP/a"; cut -d, -f15-17,19-21 "$TMP/merged" | sort > "$TMP/b"
[ "$(wc -l < "$TMP/a")" -gt 5 ] && cmp -s "$TMP/a" "$TMP/b" && ok "plan: 3 shards merge to the same errors per method" \
    || notok "plan: merged errors differ"
for i in 0 1; do "$SHLAB" $PL0 --tolerance 1e-30 --shard $i/2 > "$TMP/p$i" 2>/dev/null; done
"$SHLAB" merge "$TMP/p0" "$TMP/p1" > "$TMP/merged" 2>/dev/null; rc=$?
"$SHLAB" $PL0 --tolerance 1e-30 > "$TMP/a" 2>/dev/null; rc0=$?
[ "$rc" = 1 ] && [ "$rc0" = 1 ] && [ -s "$TMP/merged" ] && ok "plan: no method qualifies -> exit 1, unsharded and merged" \
    || notok "plan no method: exit $rc0 unsharded, $rc merged"

# --- the Slurm array script, its environment simulated ------------------------
for i in 0 1; do
    SLURM_ARRAY_TASK_ID=$i SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=1 \
        sh tools/shard_sweep.sbatch "$TMP/slurm" "$SHLAB" $TE 2>/dev/null
done
"$SHLAB" merge "$TMP"/slurm/shard-*-of-2.jsonl > "$TMP/merged" 2>/dev/null
cmp -s "$TMP/whole" "$TMP/merged" && ok "tools/shard_sweep.sbatch (array 0-1) + merge" || notok "slurm script merge differs"
SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=2 \
    sh tools/shard_sweep.sbatch "$TMP/slurm2" "$SHLAB" $TE 2>/dev/null
[ $? = 2 ] && [ ! -e "$TMP/slurm2/shard-1-of-2.jsonl" ] && ok "slurm script refuses --array=1-2" || notok "slurm script took --array=1-2"
SLURM_ARRAY_TASK_ID=0 SLURM_ARRAY_TASK_COUNT=1 sh tools/shard_sweep.sbatch "$TMP/slurm3" "$SHLAB" taylor-error --order 0 2>/dev/null
[ ! -e "$TMP/slurm3/shard-0-of-1.jsonl" ] && [ ! -e "$TMP/slurm3/shard-0-of-1.jsonl.tmp" ] \
    && ok "slurm script: a failed task leaves no shard file" || notok "slurm script left a file after a failure"

# --- merge refuses what is not one whole sweep ---------------------------------
expect_usage_error "merge: no files" merge
expect_usage_error "merge: a shard missing" merge "$TMP/t0" "$TMP/t1" "$TMP/t3"
expect_usage_error "merge: a shard twice" merge "$TMP/t0" "$TMP/t1" "$TMP/t2" "$TMP/t3" "$TMP/t1"
expect_usage_error "merge: shards of different N" merge "$TMP/t0" "$TMP/t1" "$TMP/u2" "$TMP/t3"
"$SHLAB" taylor-error --order 6 --taylor 1.5 --beta-max 31 --steps 9 --degrees --format csv --shard 2/4 > "$TMP/x2" 2>/dev/null
expect_usage_error "merge: a shard of other parameters" merge "$TMP/t0" "$TMP/t1" "$TMP/x2" "$TMP/t3"
"$SHLAB" taylor-error --order 6 --taylor 1.5 --beta-max 30 --steps 9 --degrees --format json --shard 2/4 > "$TMP/x2" 2>/dev/null
expect_usage_error "merge: a shard of another --format" merge "$TMP/t0" "$TMP/t1" "$TMP/x2" "$TMP/t3"
sed '$d' "$TMP/t2" > "$TMP/x2"
expect_usage_error "merge: a shard cut short (no end line)" merge "$TMP/t0" "$TMP/t1" "$TMP/x2" "$TMP/t3"
grep -v '"item":2,' "$TMP/t2" > "$TMP/x2"
expect_usage_error "merge: an item missing" merge "$TMP/t0" "$TMP/t1" "$TMP/x2" "$TMP/t3"
sed 's/"item":2,/"item":3,/' "$TMP/t2" > "$TMP/x2"
expect_usage_error "merge: an item of another shard" merge "$TMP/t0" "$TMP/t1" "$TMP/x2" "$TMP/t3"
{ head -2 "$TMP/t2"; sed -n 2p "$TMP/t2"; tail -n +3 "$TMP/t2"; } > "$TMP/x2"
expect_usage_error "merge: an item repeated" merge "$TMP/t0" "$TMP/t1" "$TMP/x2" "$TMP/t3"
"$SHLAB" stability --method zxzxz --lmax 9 --ref-max 4 --format csv > "$TMP/x2" 2>/dev/null
expect_usage_error "merge: not a shard file" merge "$TMP/x2"
expect_usage_error "merge: unreadable file" merge "$TMP/nonexistent"
expect_usage_error "merge: mixed sweeps" merge "$TMP/t0" "$TMP/s1" "$TMP/t2" "$TMP/t3"

# --- an experiment's --part / --shard / --merge are taken (errors only: a run is long)
BUILD=${BUILD:-build}
if make -s "$BUILD/experiments/rotation_stability" >"$TMP/log" 2>&1; then
    X="$BUILD/experiments/rotation_stability"
    "$X" "$TMP/xo" --merge "$TMP/none.items" >/dev/null 2>"$TMP/err"; rc=$?
    [ $rc = 2 ] && grep -q 'cannot open' "$TMP/err" && ok "experiment OUTDIR --merge FILE is parsed" || notok "experiment --merge: rc $rc, $(head -c 200 "$TMP/err")"
    "$X" "$TMP/xo" --part long --merge "$TMP/none.items" >/dev/null 2>"$TMP/err"; rc=$?
    [ $rc = 2 ] && grep -q 'cannot open' "$TMP/err" && ok "experiment OUTDIR --part long --merge FILE is parsed" || notok "experiment --part --merge: rc $rc, $(head -c 200 "$TMP/err")"
    "$X" "$TMP/xo" --shard 2/2 >/dev/null 2>"$TMP/err"; rc=$?
    [ $rc = 2 ] && grep -q -- '--shard' "$TMP/err" && ok "experiment --shard 2/2 refused" || notok "experiment --shard 2/2: rc $rc"
    "$X" "$TMP/xo" --part nosuch >/dev/null 2>"$TMP/err"; rc=$?
    [ $rc = 2 ] && grep -q "no part 'nosuch'" "$TMP/err" && ok "experiment --part of no such part refused" || notok "experiment --part nosuch: rc $rc"
    "$X" "$TMP/xo" --shard 0/2 --bogus >/dev/null 2>"$TMP/err"; rc=$?
    [ $rc = 2 ] && ok "experiment --shard with an extra argument refused" || notok "experiment --shard --bogus: rc $rc"
else
    notok "cannot build $BUILD/experiments/rotation_stability: $(tail -3 "$TMP/log")"
fi

# --- --shard values ----------------------------------------------------------
for bad in 2/2 -1/2 1/0 a/b 1 1/2/3 " 0/2" 0/100001; do
    expect_usage_error "--shard '$bad' refused" $TE --shard "$bad"
done
expect_success "--shard 0/1 is the whole sweep as a shard file" $TE --shard 0/1
grep -q '"shards":1' "$TMP/out" && ok "0/1 shard header" || notok "0/1 shard header"
