#!/bin/sh
# run.sh — run the libFuzzer harnesses one after the other (make fuzz).
# Usage: tests/fuzz/run.sh BUILD SECONDS HARNESS...
# Each runs SECONDS seconds (in one process, nice'd) from its seed corpus
# tests/fuzz/corpus/<h>/, keeping what it finds in BUILD/fuzz/corpus/<h>/
# (not in the repository); a crash, hang (10 s per input), leak or sanitizer
# report stops it, saves the input as BUILD/fuzz/artifacts/<h>-crash-*, and
# makes this script fail.  Prints one line per harness with the number of
# executions, and a total.
set -u
B=$1; T=$2; shift 2
total=0; failed=0
for h in "$@"; do
    mkdir -p "$B/fuzz/corpus/$h" "$B/fuzz/artifacts"
    log="$B/fuzz/$h.log"
    nice -n 10 "$B/fuzz/fuzz_$h" -max_total_time="$T" -timeout=10 -rss_limit_mb=2560 \
        -close_fd_mask=3 -print_final_stats=1 \
        -artifact_prefix="$B/fuzz/artifacts/$h-" "$B/fuzz/corpus/$h" "tests/fuzz/corpus/$h" >"$log" 2>&1
    rc=$?
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    runs=${runs:-0}
    total=$((total + runs))
    if [ "$rc" = 0 ]; then
        echo "fuzz $h: $runs executions in $T s, no crash, hang or sanitizer report"
    else
        failed=$((failed + 1))
        echo "fuzz $h: FAILED after $runs executions (exit $rc); see $log"
        grep -E 'ERROR|SUMMARY|fuzz contract|Test unit written' "$log" | head -8
    fi
done
echo "fuzz: $total executions in total, $failed harness(es) failed"
[ "$failed" = 0 ]
