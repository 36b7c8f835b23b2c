#!/bin/sh
# run.sh — run every unit-test binary (Check) and every CLI test script, then
# print one closing line "N passed, N failed".  Exit 1 if anything failed.
set -u
passed=0; failed=0
for t in "$@"; do
    out=$("$t" 2>&1); rc=$?
    printf '%s\n' "$out" | grep -E '^[0-9]+%: Checks' | sed "s|^|$(basename "$t"): |"
    printf '%s\n' "$out" | grep -E ':[EF]:' | head -50
    printf '%s\n' "$out" | grep -E '^SKIP ' | head -5
    line=$(printf '%s\n' "$out" | grep -E '^[0-9]+%: Checks' | tail -1)
    n=$(printf '%s' "$line" | sed -n 's/.*Checks: \([0-9]*\).*/\1/p')
    f=$(printf '%s' "$line" | sed -n 's/.*Failures: \([0-9]*\).*/\1/p')
    e=$(printf '%s' "$line" | sed -n 's/.*Errors: \([0-9]*\).*/\1/p')
    if [ -z "$n" ]; then
        echo "$(basename "$t"): did not report (exit $rc)"; printf '%s\n' "$out" | tail -20
        failed=$((failed + 1)); continue
    fi
    passed=$((passed + n - f - e)); failed=$((failed + f + e))
    [ "$rc" = 0 ] || [ $((f + e)) -gt 0 ] || { echo "$(basename "$t"): exit $rc"; failed=$((failed + 1)); }
done
for s in tests/cli/*.sh; do
    [ -f "$s" ] || continue
    out=$(sh "$s" 2>&1); rc=$?
    printf '%s\n' "$out" | grep -E '^(FAIL|not ok)' | head -50
    printf '%s\n' "$out" | grep -E '^SKIP ' | head -5
    p=$(printf '%s\n' "$out" | grep -c '^ok ')
    f=$(printf '%s\n' "$out" | grep -c '^not ok ')
    echo "$(basename "$s"): $p ok, $f not ok"
    passed=$((passed + p)); failed=$((failed + f))
    [ "$rc" = 0 ] || [ "$f" -gt 0 ] || { echo "$(basename "$s"): exit $rc"; failed=$((failed + 1)); }
done
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
