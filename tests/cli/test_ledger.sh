#!/bin/sh
# test_ledger.sh — the claims ledgers agree with themselves and with the
# report: reports/claims.tsv and reports/claims_timing.tsv have the form of
# experiments/common/exp.h (unique ids, a known source from
# experiments/common/sources.tsv, the verdict vocabulary, cells of at most 200
# characters, a "why: " for every verdict but reproduced), each is the
# assembly of the experiments' committed fragments, and the "Claims by
# source" tables of reports/index.md and reports/timing.md count their rows.
. "$(dirname "$0")/lib.inc"
SOURCES=experiments/common/sources.tsv
HEADER=$(printf 'claim_id\tsource\tstatement\tprinted\tmeasured\ttolerance\tverdict\tevidence')

# check_form LEDGER VERDICTS: one line per problem on stdout (none: the form holds)
check_form() {
    LC_ALL=C awk -F'\t' -v verdicts="$2" -v header="$HEADER" '
        FNR == NR { if ($0 !~ /^#/ && NF) { loc[$1] = $2; known[$1] = 1 } next }
        FNR == 1 { if ($0 != header) print "line 1: not the ledger header"; next }
        {
            where = "line " FNR " (" $1 ")"
            if (NF != 8) { print where ": " NF " cells, not 8"; next }
            if ($1 !~ /^[A-Za-z0-9][A-Za-z0-9.-]*$/) print where ": claim_id not of the form [A-Za-z0-9.-]"
            if ($1 in seen) print where ": claim_id also on line " seen[$1]
            seen[$1] = FNR
            for (i = 1; i <= 8; i++) {
                s = $i; gsub(/[\200-\277]/, "", s)     # UTF-8 characters, not bytes
                if (length(s) > 200) print where ": cell " i " has " length(s) " characters (limit 200)"
                if ($i == "" || $i ~ /^ +$/) print where ": cell " i " is empty"
            }
            w = $2; l = ""; c = index($2, ", ")
            if (c) { w = substr($2, 1, c - 1); l = substr($2, c + 2) }
            if (!(w in known)) print where ": source \"" $2 "\": \"" w "\" is not in sources.tsv"
            else if (l != "" && (loc[w] == "-" || l !~ ("^(" loc[w] ")$")))
                print where ": source \"" $2 "\": locator \"" l "\" not of the form sources.tsv gives " w
            if (index(" " verdicts " ", " " $7 " ") == 0) print where ": verdict \"" $7 "\" not one of: " verdicts
            if ($7 != "reproduced" && index($8, "why: ") == 0) print where ": verdict " $7 " without \"why: \" in the evidence"
        }' "$SOURCES" "$1"
}
# summary_check LEDGER REPORT VERDICTS: the REPORT's "Claims by source" table
# against counts made here from LEDGER; one line per difference
summary_check() {
    LC_ALL=C awk -F'\t' -v verdicts="$3" '
        FILENAME == ARGV[1] {
            if (FNR == 1) next
            w = $2; c = index(w, ", "); if (c) w = substr(w, 1, c - 1)
            n[w "|" $7]++; tot[w]++; all[$7]++; total++; next
        }
        /^## Claims by source/ { in_s = 1; next }
        in_s && /^## / { in_s = 0 }
        in_s && /^\| / {
            m = split($0, f, /[ ]*\|[ ]*/)
            if (f[2] == "source") { for (j = 3; j < m; j++) col[j] = f[j]; ncol = m; next }
            if (f[2] ~ /^-+$/ || f[2] == "") next
            rows++; w = f[2]
            if (w in listed || (w == "all" && sawall)) print "row " w " appears twice"
            if (w == "all") sawall = 1
            for (j = 3; j < ncol - 1; j++) {
                want = (w == "all") ? all[col[j]] + 0 : n[w "|" col[j]] + 0
                if (f[j] + 0 != want) print "row " w ", " col[j] ": table " f[j] ", ledger " want
            }
            want = (w == "all") ? total + 0 : tot[w] + 0
            if (f[ncol - 1] + 0 != want) print "row " w ", total: table " f[ncol - 1] ", ledger " want
            if (w != "all") listed[w] = 1
        }
        END {
            if (!rows) print "no \"Claims by source\" table"
            for (w in tot) if (!(w in listed)) print "source " w " (" tot[w] " rows) missing from the table"
            nv = split(verdicts, v, " ")
            for (j = 1; j <= nv; j++) { found = 0; for (k in col) if (col[k] == v[j]) found = 1
                if (!found && rows) print "no column for verdict " v[j] }
        }' "$1" "$2"
}

DET="reproduced differs not-applicable"
TIM="reproduced differs inconclusive not-measured not-applicable"
for pair in "reports/claims.tsv|$DET" "reports/claims_timing.tsv|$TIM"; do
    l=${pair%%|*}; v=${pair#*|}
    if [ ! -s "$l" ]; then notok "$l exists"; continue; fi
    out=$(check_form "$l" "$v")
    if [ -z "$out" ]; then ok "$l: $(($(wc -l < "$l") - 1)) rows in the ledger's form"
    else notok "$l: $(printf '%s\n' "$out" | wc -l) problems: $(printf '%s\n' "$out" | head -5 | tr '\n' ';')"; fi
done

# ids are unique across the two ledgers too
dup=$(cut -f1 reports/claims.tsv reports/claims_timing.tsv | grep -v '^claim_id$' | sort | uniq -d | tr '\n' ' ')
[ -z "$dup" ] && ok "claim ids unique across claims.tsv and claims_timing.tsv" || notok "ids in both ledgers: $dup"

# every source in sources.tsv is well formed (work, a locator ERE or -, what)
bad=$(awk -F'\t' '!/^#/ && NF && (NF != 3 || $2 == "") { print NR }' "$SOURCES" | tr '\n' ' ')
[ -z "$bad" ] && ok "sources.tsv: three cells a line" || notok "sources.tsv lines $bad"

# the summaries in index.md and timing.md count the ledgers
out=$(summary_check reports/claims.tsv reports/index.md "$DET")
[ -z "$out" ] && ok "index.md's Claims by source counts claims.tsv" || notok "index.md summary: $(printf '%s\n' "$out" | head -5 | tr '\n' ';')"
out=$(summary_check reports/claims_timing.tsv reports/timing.md "$TIM")
[ -z "$out" ] && ok "timing.md's Claims by source counts claims_timing.tsv" || notok "timing.md summary: $(printf '%s\n' "$out" | head -5 | tr '\n' ';')"

# each ledger is the assembly of the committed fragments (run_all.sh's order)
all=$(make -s --no-print-directory list-experiments 2>/dev/null)
if [ -z "$all" ]; then
    notok "make list-experiments names the experiments"
else
    : > "$TMP/det"; : > "$TMP/tim"
    for e in $all; do
        [ -f "reports/$e/claims.tsv" ] && cat "reports/$e/claims.tsv" >> "$TMP/det"
        for d in reports/"$e"/*/; do
            [ -d "$d" ] || continue
            p=$(basename "$d")
            if [ "$p" = timing ]; then [ -f "$d/claims.tsv" ] && cat "$d/claims.tsv" >> "$TMP/tim"
            else [ -f "$d/claims.tsv" ] && cat "$d/claims.tsv" >> "$TMP/det"; fi
        done
    done
    tail -n +2 reports/claims.tsv | cmp -s - "$TMP/det" && ok "claims.tsv = the experiments' fragments, in report order" \
        || notok "claims.tsv differs from its fragments (run ASSEMBLE_ONLY=1 experiments/run_all.sh)"
    tail -n +2 reports/claims_timing.tsv | cmp -s - "$TMP/tim" && ok "claims_timing.tsv = the timing fragments" \
        || notok "claims_timing.tsv differs from its fragments"
fi

# the checks themselves catch what they are for (a ledger broken on purpose)
printf '%s\n' "$HEADER" > "$TMP/bad.tsv"
printf 'x-1\tKrivanek et al. 2005, Table 1\ts\tp\tm\tt\treproduced\te\n' >> "$TMP/bad.tsv"
printf 'x-1\tissue goal\ts\tp\tm\tt\tmeasured\te\n' >> "$TMP/bad.tsv"
printf 'x-2\tKřivánek et al. 2005, Sec 3.1\ts\tp\t%0201d\tt\tdiffers\te\n' 0 >> "$TMP/bad.tsv"
out=$(check_form "$TMP/bad.tsv" "$DET")
for want in "is not in sources.tsv" "also on line" "verdict \"measured\"" "locator \"Sec 3.1\"" "(limit 200)" "without \"why: \""; do
    printf '%s\n' "$out" | grep -qF "$want" && ok "a broken row is caught: $want" || notok "not caught: $want"
done
