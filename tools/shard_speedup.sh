#!/bin/sh
# shard_speedup.sh — wall time of one sweep run as one process against the
# same sweep as N shards run by GNU parallel on this machine (plus the merge),
# alternating, ROUNDS times; checks that every merge equals the unsharded
# output byte for byte.  Prints one line per round and the load average
# before it (other processes share the cores: read the ratios as ranges).
#
#   tools/shard_speedup.sh ROUNDS N COMMAND [ARGS...]
#   tools/shard_speedup.sh 3 2 build/shlab stability --method blanco --lmax 320 --quiet
set -eu
[ $# -ge 3 ] || { echo "usage: $0 ROUNDS N COMMAND [ARGS...]" >&2; exit 2; }
rounds=$1; n=$2; shift 2
command -v parallel >/dev/null || { echo "$0: GNU parallel is not installed (Debian package parallel)" >&2; exit 2; }
shlab=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
now() { date +%s.%N; }
last=$(($n - 1))
echo "round load1 one_process_s ${n}_shards_s speedup"
r=1
while [ "$r" -le "$rounds" ]; do
    load=$(cut -d' ' -f1 /proc/loadavg)
    t0=$(now); "$@" > "$tmp/whole"; t1=$(now)
    seq 0 "$last" | parallel -j "$n" "$* --shard {}/$n > $tmp/part{}"
    "$shlab" merge "$tmp"/part* > "$tmp/merged"; t2=$(now)
    cmp -s "$tmp/whole" "$tmp/merged" || { echo "$0: round $r: the merge differs from the unsharded output" >&2; exit 1; }
    awk -v r="$r" -v l="$load" -v a="$t0" -v b="$t1" -v c="$t2" \
        'BEGIN { printf "%d %s %.1f %.1f %.2f\n", r, l, b - a, c - b, (b - a) / (c - b) }'
    rm -f "$tmp"/part*
    r=$((r + 1))
done
