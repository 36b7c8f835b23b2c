#!/bin/sh
# shard_speedup.sh — one sweep run as one process against the same sweep as
# N shards run by GNU parallel on this machine (plus the merge), alternating,
# ROUNDS times; every merge must equal the unsharded output byte for byte.
# One line per round: the 1-minute load average before it, wall seconds of
# both and their ratio (the speedup), and CPU seconds (user + system) of the
# one process, of the dearest shard and of all shards — cpu_one / cpu_max is
# the speedup N idle cores would give, cpu_sum / cpu_one the cost of sharding.
# Other processes share the cores: read the wall ratios as ranges.
#
#   tools/shard_speedup.sh ROUNDS N COMMAND [ARGS...]
#   tools/shard_speedup.sh 3 2 build/shlab stability --method blanco --lmax 320 --quiet
set -eu
[ $# -ge 3 ] || { echo "usage: $0 ROUNDS N COMMAND [ARGS...]" >&2; exit 2; }
rounds=$1; n=$2; shift 2
for t in parallel /usr/bin/time; do
    command -v $t >/dev/null || { echo "$0: $t is not installed (Debian packages parallel, time)" >&2; exit 2; }
done
shlab=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
now() { date +%s.%N; }
cpu() { awk '{ print $1 + $2 }' "$1"; }
last=$((n - 1))
echo "round load1 wall_one_s wall_${n}_shards_s speedup cpu_one_s cpu_max_shard_s cpu_sum_shards_s cpu_speedup"
r=1
while [ "$r" -le "$rounds" ]; do
    load=$(cut -d' ' -f1 /proc/loadavg)
    t0=$(now)
    /usr/bin/time -f '%U %S' -o "$tmp/cpu_one" "$@" > "$tmp/whole"
    t1=$(now)
    seq 0 "$last" | parallel -j "$n" "/usr/bin/time -f '%U %S' -o $tmp/cpu{} $* --shard {}/$n > $tmp/part{}"
    "$shlab" merge "$tmp"/part* > "$tmp/merged"
    t2=$(now)
    cmp -s "$tmp/whole" "$tmp/merged" || { echo "$0: round $r: the merge differs from the unsharded output" >&2; exit 1; }
    c1=$(cpu "$tmp/cpu_one")
    cs=$(for i in $(seq 0 "$last"); do cpu "$tmp/cpu$i"; done | tr '\n' ' ')
    echo "$cs" | awk -v r="$r" -v l="$load" -v a="$t0" -v b="$t1" -v c="$t2" -v c1="$c1" '
        { mx = 0; s = 0; for (i = 1; i <= NF; i++) { s += $i; if ($i > mx) mx = $i } }
        END { printf "%d %s %.1f %.1f %.2f %.1f %.1f %.1f %.2f\n", r, l, b - a, c - b, (b - a) / (c - b), c1, mx, s, c1 / mx }'
    rm -f "$tmp"/part* "$tmp"/cpu*
    r=$((r + 1))
done
