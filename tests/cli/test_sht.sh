#!/bin/sh
# CLI of the fast transforms (project quad and --exr latlong, reconstruct) and
# of `bench --peers`.  Truths: results independent of --threads (bitwise);
# the projection of a coefficient does not depend on the order asked for (the
# order-300 run takes two chunks of rings of different widths, the order-4 run
# one); libsharp's results (agreement printed by bench --peers); a request
# larger than the memory allowed (ulimit -v) is refused before it allocates.
. tests/cli/lib.inc

# ---- --threads: bitwise the same result
expect_success "project quad --threads 1" project --order 40 --light green --samples 100 --threads 1 --format json
cp "$TMP/out" "$TMP/t1.json"
expect_success "project quad --threads 2" project --order 40 --light green --samples 100 --threads 2 --format json
if cmp -s "$TMP/out" "$TMP/t1.json"; then ok "project quad: --threads 2 prints what --threads 1 prints"; else notok "project quad: --threads 1 and 2 differ"; fi
expect_usage_error "negative --threads" project --order 4 --light green --threads -1
expect_usage_error "--threads not a number" project --order 4 --light green --threads two

# ---- the same coefficient whatever the order: 2 chunks (order 300, 1500 nodes) vs 1 (order 4)
expect_success "project green order 4" project --order 4 --light green --format csv
cp "$TMP/out" "$TMP/o4.csv"
expect_success "project green order 300" project --order 300 --light green --format csv --quiet
bad=0
for i in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16; do
    a=$(csv_value "$TMP/o4.csv" "$i" 10); b=$(csv_value "$TMP/out" "$i" 10)
    close "$a" "$b" 1e-13 || bad=$((bad + 1))
done
if [ "$bad" = 0 ]; then ok "order 300 and order 4 give the same first 16 coefficients"; else notok "order 300 vs 4: $bad of 16 differ"; fi

# ---- reconstruct: --threads gives the same image and ringing
expect_success "reconstruct --threads 1" reconstruct --order 40 --in "$TMP/t1.json" --out "$TMP/r1.exr" --width 200 --format json --threads 1
cp "$TMP/out" "$TMP/r1.json"
expect_success "reconstruct --threads 2" reconstruct --order 40 --in "$TMP/t1.json" --out "$TMP/r2.exr" --width 200 --format json --threads 2
sed 's/r2.exr/r1.exr/' "$TMP/out" > "$TMP/r2.json"
if cmp -s "$TMP/r1.json" "$TMP/r2.json" && cmp -s "$TMP/r1.exr" "$TMP/r2.exr"; then ok "reconstruct: --threads 1 and 2 write the same file and result"; else notok "reconstruct: --threads 1 and 2 differ"; fi
expect_usage_error "reconstruct negative --threads" reconstruct --order 1 --coeffs 1 --out "$TMP/x.exr" --threads -2

# ---- a request larger than the allowed memory: one line, no output file
case "${BUILD:-build}" in
*san*) ok "memory limit (skipped: sanitizer builds need their own address space)" ;;
*)
    (ulimit -v 400000 2>/dev/null && "$SHLAB" reconstruct --order 2 --coeffs 1,0,0,0 --width 40000 --out "$TMP/big.exr") >"$TMP/out" 2>"$TMP/err"; rc=$?
    if [ "$rc" = 2 ] && [ ! -s "$TMP/out" ] && [ "$(wc -l <"$TMP/err")" = 1 ] && grep -q 'needs .* GB of memory' "$TMP/err" && [ ! -e "$TMP/big.exr" ]; then
        ok "reconstruct larger than ulimit -v is refused in one line"
    else
        notok "memory limit (exit $rc: $(head -c 200 "$TMP/err"))"
    fi ;;
esac

# ---- bench --peers
expect_usage_error "bench --peers bad --lmax" bench --peers --lmax x
expect_usage_error "bench --peers --lmax too large" bench --peers --lmax 5000
expect_usage_error "bench --peers --repeat 0" bench --peers --repeat 0
"$SHLAB" bench --peers --lmax 31,64 --repeat 3 --format csv >"$TMP/out" 2>"$TMP/err"; rc=$?
if [ "$rc" = 2 ] && grep -q 'libsharp was not found' "$TMP/err"; then
    ok "bench --peers without libsharp says so (SKIP the comparison)"
elif [ "$rc" = 0 ]; then
    rows=$(awk -F, 'NR > 1' "$TMP/out" | wc -l)
    worst=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "agreement") k = i } NR > 1 && $k > w { w = $k } END { print w + 0 }' "$TMP/out")
    if [ "$rows" = 4 ] && awk -v w="$worst" 'BEGIN { exit !(w < 1e-13) }'; then ok "bench --peers: 4 rows, shlab and libsharp agree to $worst"; else notok "bench --peers: $rows rows, agreement $worst"; fi
else
    notok "bench --peers (exit $rc: $(head -c 200 "$TMP/err"))"
fi
