#!/bin/sh
# CLI contract of `shlab eval` and `shlab convert` (docs/CONVENTIONS.md "Output").
. tests/cli/lib.inc

expect_success "shlab --help" --help
expect_success "eval --help" eval --help
expect_success "convert --help" convert --help
expect_usage_error "no command"
expect_usage_error "unknown command" frobnicate
expect_usage_error "eval order 0" eval --order 0 --dir 0,0,1
expect_usage_error "eval order too large" eval --order 5000 --dir 0,0,1
expect_usage_error "eval order not a number" eval --order 3x --dir 0,0,1
expect_usage_error "eval zero direction" eval --order 3 --dir 0,0,0
expect_usage_error "eval NaN direction" eval --order 3 --dir nan,0,1
expect_usage_error "eval Inf direction" eval --order 3 --dir 1,inf,0
expect_usage_error "eval direction with 2 numbers" eval --order 3 --dir 1,0
expect_usage_error "eval NaN theta" eval --order 3 --theta nan --phi 0
expect_usage_error "eval theta without phi" eval --order 3 --theta 1
expect_usage_error "eval unknown option" eval --order 3 --dir 0,0,1 --bogus
expect_usage_error "eval missing value" eval --order
expect_usage_error "eval bad format" eval --order 3 --dir 0,0,1 --format xml
expect_usage_error "eval bad convention" eval --order 3 --dir 0,0,1 --convention xyz
expect_usage_error "eval stray argument" eval --order 3 --dir 0,0,1 extra

# y_1^0 at the north pole is sqrt(3/4pi) = 0.48860251190291992
expect_success "eval json" eval --order 2 --dir 0,0,5 --format json
expect_success "eval csv" eval --order 2 --dir 0,0,5 --format csv
if close "$(csv_value "$TMP/out" 3 6)" 0.48860251190291992 1e-15; then ok "eval pole value sqrt(3/4pi)"; else notok "eval pole value: $(cat "$TMP/out")"; fi
# degrees: theta=90, phi=90 -> direction +y; cs: y_1^-1 = -sqrt(3/4pi)
expect_success "eval degrees" eval --order 2 --theta 90 --phi 90 --degrees --format csv
if close "$(csv_value "$TMP/out" 2 6)" -0.48860251190291992 1e-15 && close "$(csv_value "$TMP/out" 3 6)" 0 1e-15; then ok "eval degrees +y cs sign"; else notok "eval degrees: $(cat "$TMP/out")"; fi
expect_success "eval nocs" eval --order 2 --dir 0,1,0 --convention nocs --format csv
if close "$(csv_value "$TMP/out" 2 6)" 0.48860251190291992 1e-15; then ok "eval nocs +y positive (Ivanic p_y)"; else notok "eval nocs: $(cat "$TMP/out")"; fi

# convert: cs -> nocs flips odd m
expect_success "convert cs->nocs" convert --from cs --to nocs --coeffs 1,2,3,4 --format csv
if [ "$(cut -d, -f8 "$TMP/out" | tail -4 | tr '\n' ' ')" = "1 -2 3 -4 " ]; then ok "convert flips odd m"; else notok "convert flips: $(cat "$TMP/out")"; fi
expect_success "convert cs->schmidt" convert --from cs --to schmidt --coeffs 1,0,1,0 --format csv
# schmidt coefficient = c * sqrt((2l+1)/4pi): l=0 -> 0.28209479177387814, l=1 -> 0.48860251190291992
if close "$(csv_value "$TMP/out" 1 8)" 0.28209479177387814 1e-15 && close "$(csv_value "$TMP/out" 3 8)" 0.48860251190291992 1e-15; then ok "convert schmidt scale"; else notok "convert schmidt: $(cat "$TMP/out")"; fi
# the output names its convention in full (it once said "nocs" for a Schmidt vector)
expect_success "convert cs->schmidt json" convert --from cs --to schmidt --coeffs 1,0,1,0 --format json
case $(cat "$TMP/out") in *'"convention":"schmidt"'*) ok "convert's output names schmidt" ;; *) notok "convert convention: $(cat "$TMP/out")" ;; esac
expect_usage_error "convert not square" convert --from cs --to nocs --coeffs 1,2,3
expect_usage_error "convert bad norm" convert --from cs --to foo --coeffs 1
expect_usage_error "convert NaN" convert --from cs --to nocs --coeffs 1,nan,0,0
expect_usage_error "convert missing file" convert --from cs --to nocs --in "$TMP/nope.json"
echo '{"coeffs": [1, 2' > "$TMP/bad.json"
expect_usage_error "convert corrupt json" convert --from cs --to nocs --in "$TMP/bad.json"
echo '{"channels": {"R":[1,2,3,4],"G":[0,0,0,1]}}' > "$TMP/ch.json"
expect_success "convert channels file" convert --from cs --to nocs --in "$TMP/ch.json" --format json
if grep -q '"G":\[0.0,0.0,0.0,-1.0\]' "$TMP/out"; then ok "convert channels"; else notok "convert channels: $(cat "$TMP/out")"; fi

# review regressions: NUL bytes, over-long channel names (would collide when
# truncated), write errors on stdout, CSV quoting of strings with commas
printf '1 2 3 4\0 5' > "$TMP/nul.txt"
expect_usage_error "convert file with a NUL byte" convert --from cs --to nocs --in "$TMP/nul.txt"
echo '{"channels":{"RRRRRRRRa":[1,0,0,0],"RRRRRRRRb":[2,0,0,0]}}' > "$TMP/long.json"
expect_usage_error "convert channel name too long" convert --from cs --to nocs --in "$TMP/long.json"
if [ -w /dev/full ]; then
    "$SHLAB" --help > /dev/full 2>/dev/null; rc=$?
    if [ "$rc" = 2 ]; then ok "--help to a full device fails"; else notok "--help to /dev/full exit $rc"; fi
    "$SHLAB" eval --order 2 --dir 0,0,1 > /dev/full 2>/dev/null; rc=$?
    if [ "$rc" = 2 ]; then ok "eval to a full device fails"; else notok "eval to /dev/full exit $rc"; fi
fi
expect_success "csv quoting" project --order 1 --light cie-clear:0.5,1 --format csv
if [ "$(awk -F'"' 'NR == 2 { print $2 }' "$TMP/out")" = "cie-clear:0.5,1" ]; then ok "csv quotes a string with a comma"; else notok "csv quoting: $(cat "$TMP/out")"; fi
