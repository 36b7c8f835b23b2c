#!/bin/sh
# run.sh — run every unit-test binary (Check) and every CLI test script, then
# print one closing line "N passed, N failed".  Exit 1 if anything failed.
# Each test's summary line ends with its wall time.  TEST_JOBS=J (default 1)
# runs J tests at a time (the lines still come in the order given); the
# timing-sensitive scripts (signals, progress) run alone at the end.
set -u
jobs=${TEST_JOBS:-1}
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
serial_scripts="test_signals.sh"
i=0
list=$dir/list
: >"$list"
for t in "$@"; do i=$((i + 1)); printf '%s bin %s\n' "$i" "$t" >>"$list"; done
# SKIP_SCRIPTS: script names left out of this run (make check SANITIZE=1
# leaves out those whose code under test is not instrumented; the plain check
# runs them), each said so
skip=" ${SKIP_SCRIPTS:-} "
for s in tests/cli/*.sh; do
    [ -f "$s" ] || continue
    case " $serial_scripts " in *" $(basename "$s") "*) continue ;; esac
    case "$skip" in *" $(basename "$s") "*) echo "$(basename "$s"): skipped in this run (SKIP_SCRIPTS)"; continue ;; esac
    i=$((i + 1)); printf '%s sh %s\n' "$i" "$s" >>"$list"
done
serial=$dir/serial
: >"$serial"
for s in $serial_scripts; do
    [ -f "tests/cli/$s" ] || continue
    i=$((i + 1)); printf '%s sh %s\n' "$i" "tests/cli/$s" >>"$serial"
done
xargs -P "$jobs" -L 1 sh tests/run_one.sh "$dir" <"$list"
xargs -P 1 -L 1 sh tests/run_one.sh "$dir" <"$serial"
passed=0; failed=0
for k in $(seq 1 "$i"); do
    [ -f "$dir/$k.out" ] || { echo "test $k did not run"; failed=$((failed + 1)); continue; }
    cat "$dir/$k.out"
    read -r p f <"$dir/$k.count"
    passed=$((passed + p)); failed=$((failed + f))
done
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
