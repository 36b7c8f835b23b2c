#!/bin/sh
# run_all.sh [NAME...] — run the named experiments, render their gnuplot
# scripts, and assemble the report from the fragments of EVERY experiment
# (ALL_EXPERIMENTS, in report order; the ones not named are taken as
# committed), so running one experiment replaces only its own sections:
#   reports/index.md, reports/claims.tsv      deterministic: the same code
#       writes the same bytes (each experiment's folder, and its kept parts,
#       e.g. probes/ and instructions/, which are regenerated only when their
#       input or tool is there and otherwise left as committed);
#   reports/timing.md, reports/claims_timing.tsv   machine-dependent (the
#       timing/ part of each experiment), rewritten by every run of it.
# See experiments/common/exp.h for the parts and docs/experiments.md for the
# ways to run it (`make report [EXPERIMENTS=...]`, `make plots`).
#
# Environment: REV names the code revision; BUILD the build folder;
# ALL_EXPERIMENTS every experiment in report order (default: the Makefile's
# list, `make -s list-experiments`); RENDER_ONLY=1 renders the named
# experiments' plots from their committed data without running them;
# ASSEMBLE_ONLY=1 runs and renders nothing, only assembles.
set -eu
BUILD=${BUILD:-build}
REV=${REV:-unknown}
export REV
if [ -z "${ALL_EXPERIMENTS:-}" ]; then
    ALL_EXPERIMENTS=$(make -s --no-print-directory list-experiments)
fi
SOURCES=experiments/common/sources.tsv
mkdir -p reports
failed=""

for name in "$@"; do
    case " $(echo $ALL_EXPERIMENTS) " in
        *" $name "*) ;;
        *) echo "run_all.sh: unknown experiment '$name' (known: $(echo $ALL_EXPERIMENTS))" >&2; exit 2 ;;
    esac
done

# render NAME: NAME.gp renders into reports/NAME, NAME.PART.gp into
# reports/NAME/PART (skipped while that part has never been computed)
render() {
    for gp in experiments/"$1"/*.gp; do
        [ -f "$gp" ] || continue
        part=$(basename "$gp" .gp)
        part=${part#"$1"}
        part=${part#.}
        dir=reports/$1${part:+/$part}
        [ -d "$dir" ] || continue
        if ! gnuplot -e "outdir='$dir'" "$gp"; then
            echo "gnuplot $gp FAILED" >&2
            failed="$failed $1:$(basename "$gp")"
        fi
    done
}

if [ "${ASSEMBLE_ONLY:-0}" != 1 ]; then
    for name in "$@"; do
        if [ "${RENDER_ONLY:-0}" = 1 ]; then
            render "$name"
            continue
        fi
        out=reports/$name
        mkdir -p "$out"
        echo "== experiment $name" >&2
        start=$(date +%s)
        stamp=$(mktemp)
        if ! "$BUILD/experiments/$name" "$out"; then
            echo "experiment $name FAILED" >&2
            failed="$failed $name"
            rm -f "$stamp"
            continue
        fi
        # the machine of this run's timings (timing.md names it per section),
        # when this run measured them (wrote timing data; a part it could not
        # measure, e.g. without an input, keeps its earlier data and machine)
        if [ -n "$(find "$out/timing" -maxdepth 1 -name '*.dat' -newer "$stamp" 2>/dev/null)" ]; then
            cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -1)
            cc_version=$(${CC:-cc} --version 2>/dev/null | head -1)
            printf '%s, code revision `%s`, %s, %s, %s cores, load average %s, compiled by %s (-O2)\n' \
                "$(date -u +%Y-%m-%d)" "$REV" "$(uname -m)" "${cpu:-unknown CPU}" "$(nproc)" \
                "$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)" \
                "${cc_version:-an unknown compiler}" > "$out/timing/machine.txt"
        fi
        rm -f "$stamp"
        render "$name"
        echo "   $name done in $(( $(date +%s) - start )) s" >&2
    done
fi

# fragment FILE PREFIX: a fragment with its relative links made relative to reports/
fragment() {
    sed -E "s#\]\(([^/):]+\.(png|dat|tsv|exr|md|txt))\)#](${2}/\1)#g" "$1"
}
# parts NAME: the kept parts of an experiment (subfolders other than timing/)
parts() {
    for d in reports/"$1"/*/; do
        [ -d "$d" ] || continue
        p=$(basename "$d")
        [ "$p" = timing ] || echo "$p"
    done
}
# summary LEDGER VERDICT...: the rows of LEDGER counted per source and
# verdict, as a Markdown table.  The source is the work named before the first
# ", " of the source cell; works in the order of experiments/common/sources.tsv
# (a work not listed there comes last, so that the ledger test reports it).
summary() {
    ledger=$1; shift
    awk -F'\t' -v verdicts="$*" '
        FNR == NR { if ($0 !~ /^#/ && NF) { order[++nw] = $1; known[$1] = 1 } next }
        FNR == 1 { next }
        {
            w = $2; i = index(w, ", "); if (i) w = substr(w, 1, i - 1)
            if (!(w in seen)) { seen[w] = 1; if (!(w in known)) extra[++ne] = w }
            n[w, $7]++; tot[w]++; all[$7]++; total++
        }
        BEGIN { nv = split(verdicts, v, " ") }
        END {
            printf "| source |"; for (j = 1; j <= nv; j++) printf " %s |", v[j]; print " total |"
            printf "|---|"; for (j = 1; j <= nv; j++) printf "---|"; print "---|"
            for (k = 1; k <= nw + ne; k++) {
                w = k <= nw ? order[k] : extra[k - nw]
                if (!(w in tot)) continue
                printf "| %s |", w; for (j = 1; j <= nv; j++) printf " %d |", n[w, v[j]]; printf " %d |\n", tot[w]
            }
            printf "| all |"; for (j = 1; j <= nv; j++) printf " %d |", all[v[j]]; printf " %d |\n", total
        }' "$SOURCES" "$ledger"
}

# ---- reports/claims.tsv (deterministic) -------------------------------------
header='claim_id\tsource\tstatement\tprinted\tmeasured\ttolerance\tverdict\tevidence\n'
{
    printf "$header"
    for name in $ALL_EXPERIMENTS; do
        if [ -f "reports/$name/claims.tsv" ]; then cat "reports/$name/claims.tsv"; fi
        for p in $(parts "$name"); do
            if [ -f "reports/$name/$p/claims.tsv" ]; then cat "reports/$name/$p/claims.tsv"; fi
        done
    done
} > reports/claims.tsv.tmp && mv reports/claims.tsv.tmp reports/claims.tsv

# ---- reports/index.md (deterministic) --------------------------------------
{
    echo "# shlab report"
    echo
    echo "Assembled by \`make report\` at code revision \`$REV\` (the last commit that changed code or"
    echo "data; committing regenerated reports does not change it). Every number below was measured"
    echo "by the experiment named in its section; the data files (with their column headers, the"
    echo "revision and the command that wrote them) sit beside the plots. An experiment run alone"
    echo "(\`make report EXPERIMENTS=NAME\`, docs/experiments.md) replaces only its own sections; the"
    echo "others are assembled as committed. The claims ledger is [claims.tsv](claims.tsv)."
    echo
    echo "Everything in this file and in the ledger is deterministic: the same code writes the same"
    echo "bytes. Results of optional inputs (the HDR probes of \`make probes\`, valgrind's instruction"
    echo "counts) are regenerated when the input is there and otherwise kept, each naming the revision"
    echo "that computed it. Timings depend on the machine and its load: they are in"
    echo "[timing.md](timing.md) and [claims_timing.tsv](claims_timing.tsv)."
    echo
    echo "## Claims by source"
    echo
    echo "The rows of [claims.tsv](claims.tsv) counted per source (the work before the first comma of"
    echo "the \`source\` cell; the list of sources is experiments/common/sources.tsv) and verdict. A"
    echo "\"differs\" or \"not-applicable\" row says why in its \`evidence\` cell; the speed claims are"
    echo "counted in [timing.md](timing.md)."
    echo
    summary reports/claims.tsv reproduced differs not-applicable
    echo
    for name in $ALL_EXPERIMENTS; do
        have=0
        [ -f "reports/$name/index.md" ] && have=1
        for p in $(parts "$name"); do [ -f "reports/$name/$p/index.md" ] && have=1; done
        [ -f "reports/$name/timing/index.md" ] && have=1
        [ $have = 1 ] || continue
        echo "## $name"
        echo
        [ -f "reports/$name/index.md" ] && fragment "reports/$name/index.md" "$name"
        for p in $(parts "$name"); do
            [ -f "reports/$name/$p/index.md" ] && fragment "reports/$name/$p/index.md" "$name/$p"
        done
        if [ -f "reports/$name/timing/index.md" ]; then
            echo "Timings of this experiment (machine-dependent): [timing.md, $name](timing.md#$name)."
            echo
        fi
    done
} > reports/index.md.tmp && mv reports/index.md.tmp reports/index.md

# ---- reports/claims_timing.tsv and timing.md (machine-dependent) ------------
{
    printf "$header"
    for name in $ALL_EXPERIMENTS; do
        if [ -f "reports/$name/timing/claims.tsv" ]; then cat "reports/$name/timing/claims.tsv"; fi
    done
} > reports/claims_timing.tsv.tmp && mv reports/claims_timing.tsv.tmp reports/claims_timing.tsv
{
    echo "# shlab timings (machine-dependent)"
    echo
    echo "Each experiment's \`timing/\` part, as it was measured when that experiment last ran: every"
    echo "run of an experiment rewrites its part (machine, revision and date below each heading, and"
    echo "in the headers of its data files), the others are assembled as committed. Times are"
    echo "interleaved in one process and ratios are paired (median of per-round ratios,"
    echo "\`sh_bench_interleaved\`); a run that breaks the noise criterion (docs/rotation.md, \"Rotation speed\")"
    echo "publishes its speed claims as \"not-measured\"."
    echo
    echo "## Claims by source"
    echo
    echo "The speed claims of [claims_timing.tsv](claims_timing.tsv) counted per source and verdict (as"
    echo "in index.md):"
    echo
    summary reports/claims_timing.tsv reproduced differs inconclusive not-measured not-applicable
    echo
    for name in $ALL_EXPERIMENTS; do
        [ -f "reports/$name/timing/index.md" ] || continue
        echo "## $name"
        echo
        if [ -f "reports/$name/timing/machine.txt" ]; then
            echo "Measured on $(cat "reports/$name/timing/machine.txt")."
        else
            echo "Measured before the runs recorded their machine here: the data files' headers name it."
        fi
        echo
        fragment "reports/$name/timing/index.md" "$name/timing"
    done
} > reports/timing.md.tmp && mv reports/timing.md.tmp reports/timing.md

n=$(($(wc -l < reports/claims.tsv) - 1))
nt=$(($(wc -l < reports/claims_timing.tsv) - 1))
echo "report: reports/index.md, reports/claims.tsv ($n claims); reports/timing.md, reports/claims_timing.tsv ($nt speed claims)" >&2
if [ -n "$failed" ]; then
    echo "report: FAILED:$failed" >&2
    exit 1
fi
