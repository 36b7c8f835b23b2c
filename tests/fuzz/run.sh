#!/bin/sh
# run.sh — run the libFuzzer harnesses one after the other (make fuzz).
# Usage: [FUZZ_RUNS=N] tests/fuzz/run.sh BUILD SECONDS HARNESS...
# Each runs SECONDS seconds (0: no time limit) or, with FUZZ_RUNS=N, until N
# executions, whichever comes first (in one process, nice'd, one thread) from
# its seed corpus tests/fuzz/corpus/<h>/, keeping what it finds in
# BUILD/fuzz/corpus/<h>/ (not in the repository); a crash, hang (10 s per
# input), leak or sanitizer report stops it, saves the input as
# BUILD/fuzz/artifacts/<h>-crash-*, and makes this script fail.  Prints one
# line per harness (executions, wall time, executions per second, coverage
# as libFuzzer's cov/ft, corpus size) and a total; after a failure, the
# harness's contract message (replaying the saved input).
set -u
B=$1; T=$2; shift 2
runs_opt=; [ -n "${FUZZ_RUNS:-}" ] && runs_opt="-runs=$FUZZ_RUNS"
total=0; failed=0
for h in "$@"; do
    mkdir -p "$B/fuzz/corpus/$h" "$B/fuzz/artifacts"
    log="$B/fuzz/$h.log"
    t0=$(date +%s)
    OMP_NUM_THREADS=1 nice -n 10 "$B/fuzz/fuzz_$h" -max_total_time="$T" $runs_opt -timeout=10 \
        -rss_limit_mb=2560 -close_fd_mask=3 -print_final_stats=1 \
        -artifact_prefix="$B/fuzz/artifacts/$h-" "$B/fuzz/corpus/$h" "tests/fuzz/corpus/$h" >"$log" 2>&1
    rc=$?
    secs=$(( $(date +%s) - t0 ))
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    runs=${runs:-0}
    total=$((total + runs))
    # the last status line: "#N DONE cov: C ft: F corp: K/S lim: ... exec/s: R ..."
    st=$(grep -E '^#[0-9]+' "$log" | tail -1 | sed -n 's/.*cov: \([0-9]*\) ft: \([0-9]*\) corp: \([0-9]*\)\/\([^ ]*\).*/cov \1, ft \2, corpus \3 inputs (\4)/p')
    rate=$(( runs / (secs > 0 ? secs : 1) ))
    if [ "$rc" = 0 ]; then
        echo "fuzz $h: $runs executions in $secs s ($rate/s), ${st:-no status line}, no crash, hang or sanitizer report"
    else
        failed=$((failed + 1))
        echo "fuzz $h: FAILED after $runs executions in $secs s (exit $rc); see $log"
        grep -E 'ERROR|SUMMARY|fuzz contract|Test unit written' "$log" | head -8
        # -close_fd_mask hid the harness's own message: replay the input once
        for a in $(sed -n "s/.*Test unit written to \(.*\)$/\1/p" "$log"); do
            "$B/fuzz/fuzz_$h" "$a" 2>&1 | grep -E '^fuzz contract' | head -1
        done
    fi
done
echo "fuzz: $total executions in total, $failed harness(es) failed"
[ "$failed" = 0 ]
