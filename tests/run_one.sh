#!/bin/sh
# run_one.sh DIR K KIND TEST — one test of run.sh: runs TEST (KIND bin: a
# Check binary; sh: a CLI script), writes its report lines to DIR/K.out and
# "passed failed" to DIR/K.count.
set -u
dir=$1; k=$2; kind=$3; t=$4
t0=$(date +%s.%N)
if [ "$kind" = bin ]; then out=$("$t" 2>&1); else out=$(sh "$t" 2>&1); fi
rc=$?
secs=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
name=$(basename "$t")
p=0; f=0
{
if [ "$kind" = bin ]; then
    printf '%s\n' "$out" | grep -E '^[0-9]+%: Checks' | sed "s|^|$name: |; s|\$| ($secs s)|"
    printf '%s\n' "$out" | grep -E ':[EF]:' | head -50
    printf '%s\n' "$out" | grep -E '^SKIP ' | head -5
    line=$(printf '%s\n' "$out" | grep -E '^[0-9]+%: Checks' | tail -1)
    n=$(printf '%s' "$line" | sed -n 's/.*Checks: \([0-9]*\).*/\1/p')
    fl=$(printf '%s' "$line" | sed -n 's/.*Failures: \([0-9]*\).*/\1/p')
    e=$(printf '%s' "$line" | sed -n 's/.*Errors: \([0-9]*\).*/\1/p')
    if [ -z "$n" ]; then
        echo "$name: did not report (exit $rc)"; printf '%s\n' "$out" | tail -20
        f=1
    else
        p=$((n - fl - e)); f=$((fl + e))
        [ "$rc" = 0 ] || [ "$f" -gt 0 ] || { echo "$name: exit $rc"; f=$((f + 1)); }
    fi
else
    printf '%s\n' "$out" | grep -E '^(FAIL|not ok)' | head -50
    printf '%s\n' "$out" | grep -E '^SKIP ' | head -5
    p=$(printf '%s\n' "$out" | grep -c '^ok ')
    f=$(printf '%s\n' "$out" | grep -c '^not ok ')
    echo "$name: $p ok, $f not ok ($secs s)"
    [ "$rc" = 0 ] || [ "$f" -gt 0 ] || { echo "$name: exit $rc"; f=$((f + 1)); }
fi
} >"$dir/$k.out"
echo "$p $f" >"$dir/$k.count"
