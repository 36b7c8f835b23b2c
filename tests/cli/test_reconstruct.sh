#!/bin/sh
# CLI contract of `shlab reconstruct` (docs/CONVENTIONS.md "Output"): errors exit 2
# with one "shlab: error:" line, nothing on stdout and no output file left.
. tests/cli/lib.inc

# expect_no_file "what" FILE : neither FILE nor a FILE.tmp.* is left
expect_no_file() {
    if [ ! -e "$2" ] && [ -z "$(ls "$2".tmp.* 2>/dev/null)" ]; then ok "$1"; else notok "$1 ($2 exists)"; fi
}

OUT="$TMP/r.exr"
expect_success "reconstruct --help" reconstruct --help
expect_usage_error "no order" reconstruct --coeffs 1 --out "$OUT"
expect_no_file "no order leaves no file" "$OUT"
expect_usage_error "no --out" reconstruct --order 1 --coeffs 1
expect_usage_error "both --coeffs and --in" reconstruct --order 1 --coeffs 1 --in "$TMP/x" --out "$OUT"
expect_usage_error "neither --coeffs nor --in" reconstruct --order 1 --out "$OUT"
expect_usage_error "not a square" reconstruct --order 1 --coeffs 1,2 --out "$OUT"
expect_usage_error "order above the vector's" reconstruct --order 3 --coeffs 1,0,0,0 --out "$OUT"
expect_usage_error "NaN coefficient" reconstruct --order 2 --coeffs 1,nan,0,0 --out "$OUT"
expect_usage_error "bad window" reconstruct --order 2 --coeffs 1,0,0,0 --window box:3 --out "$OUT"
expect_usage_error "negative gauss" reconstruct --order 2 --coeffs 1,0,0,0 --window gauss:-1 --out "$OUT"
expect_usage_error "width 1" reconstruct --order 2 --coeffs 1,0,0,0 --width 1 --out "$OUT"
expect_usage_error "width not a number" reconstruct --order 2 --coeffs 1,0,0,0 --width 12x --out "$OUT"
expect_usage_error "bad convention" reconstruct --order 2 --coeffs 1,0,0,0 --convention up --out "$OUT"
expect_usage_error "missing --in file" reconstruct --order 1 --in "$TMP/nope.json" --out "$OUT"
echo '{"channels": {"R":[1,2,3,4],"G":[0,0,0,1]}}' > "$TMP/two.json"
expect_usage_error "two channels" reconstruct --order 2 --in "$TMP/two.json" --out "$OUT"
expect_usage_error "unwritable --out" reconstruct --order 2 --coeffs 1,0,0,0 --out "$TMP/no/such/dir/r.exr"
expect_no_file "unwritable --out leaves nothing" "$TMP/no/such/dir/r.exr"
expect_usage_error "overflowing coefficients" reconstruct --order 1 --coeffs 1e300 --out "$OUT"
expect_no_file "no file after any error" "$OUT"

# success: f = 2·sqrt(4π)·y_0 = 2 everywhere, truncated from an order-2 vector
expect_success "constant, json" reconstruct --order 1 --coeffs 7.0898154036220635,5,5,5 --out "$OUT" --width 16 --format json
if grep -q '"width":16,"height":8' "$TMP/out" && grep -q '"most_negative":0.0' "$TMP/out" \
   && grep -q '"negative_energy_fraction":0.0' "$TMP/out"; then ok "constant: size and no ringing"; else notok "constant: $(cat "$TMP/out")"; fi
if [ -s "$OUT" ] && [ "$(head -c 4 "$OUT" | od -An -tx1 | tr -d ' ')" = "762f3101" ]; then ok "wrote an EXR (magic)"; else notok "no EXR written"; fi
# the written file can be projected back (shlab project --exr, when present)
if "$SHLAB" project --help 2>/dev/null | grep -q -- '--exr'; then
    expect_success "project the EXR back" project --order 1 --exr "$OUT" --format csv
    v=$(awk -F, 'NR == 2 { print $NF }' "$TMP/out")
    if close "$v" 7.0898154036220635 1e-6; then ok "round trip c0 = 2·sqrt(4π)"; else notok "round trip c0: $(cat "$TMP/out")"; fi
fi

# y_1^0 with amplitude 3: f = 3·sqrt(3/4π)·cosθ, most negative near −1.4658 at the
# bottom row centre θ = π(1 − 1/(2H)); the negative half holds half the energy
expect_success "dipole csv" reconstruct --order 2 --coeffs 0,0,3,0 --out "$OUT" --width 64 --format csv
mn=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "most_negative") c = i } NR == 2 { print $c }' "$TMP/out")
fr=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "negative_energy_fraction") c = i } NR == 2 { print $c }' "$TMP/out")
want=$(awk 'BEGIN { pi = atan2(0, -1); printf "%.17g", -3 * sqrt(3 / (4 * pi)) * cos(pi / 64) }')
if close "$mn" "$want" 1e-9; then ok "dipole most negative"; else notok "dipole most negative $mn vs $want"; fi
if close "$fr" 0.5 1e-12; then ok "dipole negative energy fraction 1/2"; else notok "dipole fraction $fr"; fi

# channels file → RGB EXR; hann window makes the constant image unchanged
echo '{"channels": {"R":[3.5449077018110318,0,0,0],"G":[0,0,0,0],"B":[1,0,0,0]}}' > "$TMP/rgb.json"
expect_success "rgb channels file" reconstruct --order 2 --in "$TMP/rgb.json" --out "$OUT" --window hann --format json
if grep -q '"window":"hann"' "$TMP/out"; then ok "window echoed"; else notok "window: $(cat "$TMP/out")"; fi
if [ -s "$OUT" ]; then ok "rgb EXR written"; else notok "rgb EXR missing"; fi

# Output through a symbolic link writes the link's target (the link stays a
# link); a non-regular file (FIFO) is refused, not replaced (review 1.1).
: > "$TMP/target.exr"; ln -s target.exr "$TMP/link.exr"
if "$SHLAB" reconstruct --order 2 --coeffs 1,0,0,0 --width 8 --out "$TMP/link.exr" >/dev/null 2>&1 &&
   [ -L "$TMP/link.exr" ] && [ -s "$TMP/target.exr" ]; then ok "output via symlink keeps the link"; else notok "output via symlink"; fi
mkfifo "$TMP/fifo"
expect_usage_error "output to a FIFO is refused" reconstruct --order 2 --coeffs 1,0,0,0 --width 8 --out "$TMP/fifo"
if [ -p "$TMP/fifo" ] && [ -z "$(ls "$TMP" | grep 'fifo.tmp')" ]; then ok "FIFO left in place, no temp file"; else notok "FIFO replaced or temp left"; fi
