#!/bin/sh
# test_doc_figures.sh — a figure written in README.md or docs/*.md is one the
# reports hold (tests/cli/doc_figures.py says exactly what counts: numbers in
# prose, tables and ```text blocks, matched to reports/ and the console
# examples' outputs at the figure's own significant digits; the exceptions
# with their reasons in tests/cli/doc_figures_exempt.tsv).
. "$(dirname "$0")/lib.inc"
PY=${PYTHON:-python3}
ROOT=$(pwd)

if out=$("$PY" tests/cli/doc_figures.py "$ROOT" 2>&1); then ok "every README/docs figure is held by reports/ or a console example"
else notok "figures the reports do not hold (fix the page or the report; a non-measurement goes in doc_figures_exempt.tsv):"; printf '%s\n' "$out" | sed 's/^/#   /'; fi

# the check sees a drifted figure: the same tree with one figure of
# docs/findings.md changed in its last digit
mkdir -p "$TMP/root/docs" "$TMP/root/tests"
ln -s "$ROOT/reports" "$TMP/root/reports"
ln -s "$ROOT/tests/cli" "$TMP/root/tests/cli"
cp "$ROOT/README.md" "$TMP/root/"
cp "$ROOT"/docs/*.md "$TMP/root/docs/"
fig=$(grep -o 'exact −0\.[0-9]*' docs/findings.md | head -1 | sed 's/exact −//')
if [ -z "$fig" ]; then notok "docs/findings.md no longer quotes Green's y_3^-3 (pick another figure for this check)"
else
    last=$(printf '%s' "$fig" | tail -c 1); new=$(printf '%s' "$fig" | sed "s/.\$/$(( (last + 3) % 10 ))/")
    sed "s/exact −$fig/exact −$new/" docs/findings.md > "$TMP/root/docs/findings.md"
    out=$("$PY" tests/cli/doc_figures.py "$TMP/root" 2>&1); rc=$?
    case "$rc:$out" in 1:*"docs/findings.md:"*": −$new"*|1:*"docs/findings.md:"*": $new"*) ok "a figure changed from $fig to $new is caught" ;;
        *) notok "changing $fig to $new in docs/findings.md: exit $rc, $out" ;; esac
fi

# the figures that once drifted from the reports are not quoted again
for f in '3113 / 6401' '12727 / 54405' '313 / 889' '356 / 1268' '3.15 (3.12' '1.7–2.1×' '463 / 345' '0.10 [0.07, 0.28]'; do
    if grep -rqF -- "$f" README.md docs/; then notok "README/docs quote the stale figure '$f'"; else ok "stale figure '$f' gone"; fi
done
