#!/bin/sh
# test_contract.sh — the exit-2 contract on bad input, one case each:
# exit 2, exactly one line "shlab: error: ..." on stderr, nothing on stdout,
# no partial output file, no pre-existing file removed or truncated, no
# temporary file left behind; and the inputs that used to crash.
. "$(dirname "$0")/lib.inc"
FX=data/fixtures/rotation
SEEDS=tests/fuzz/corpus
# no temporary file anywhere under a directory
no_tmp() { [ -z "$(find "$1" -name '*.tmp.*' 2>/dev/null)" ]; }

# ---- valid EXR layouts that crashed OpenEXRCore's unpacker (half RGBA, A/Y/Z,
# BGRZ): every compression reads
for f in $SEEDS/exr/rgba-half-scan-*.exr $SEEDS/exr/ayz-half-scan-*.exr $SEEDS/exr/bgrz-half-ripmap-*.exr; do
    expect_success "project --exr $(basename "$f")" project --order 2 --exr "$f" --format json
done
expect_success "plan --exr half RGBA" plan --order auto --exr $SEEDS/exr/rgba-half-scan-piz.exr --tolerance 0.5 --max-beta 0.1 --quiet --format json

# ---- sizes are checked against the file before anything is allocated
# (8192×8192 = SH_IMAGE_MAX_PIXELS, the largest image read: the checks
# after the pixel count; 32768×32768 is refused by the pixel count itself)
expect_usage_error "733-byte EXR claiming 8192x8192" project --order 2 --exr $SEEDS/exr/huge-window-8k-scan.exr
grep -q "needs at least" "$TMP/err" && ok "size error names what is needed" || notok "size error: $(cat "$TMP/err")"
expect_usage_error "1.4 kB EXR with one 8192x8192 tile" project --order 2 --exr $SEEDS/exr/huge-window-8k-tile.exr
grep -q "805.3 MB" "$TMP/err" && ok "ratio error names the size asked for" || notok "ratio error: $(cat "$TMP/err")"
expect_usage_error "733-byte EXR claiming 32768x32768" project --order 2 --exr $SEEDS/exr/huge-window-scan.exr
grep -q "at most 67108864 pixels" "$TMP/err" && ok "pixel-count error names the limit" || notok "pixel error: $(cat "$TMP/err")"

# ---- no error removes or truncates an existing file; nothing left behind
mkdir -p "$TMP/o"
printf 'keep me' >"$TMP/o/old.exr"
"$SHLAB" reconstruct --order 2 --coeffs 1,0.5,0,0 --width 16 --out "$TMP/o/old.exr" >/dev/full 2>"$TMP/err"; rc=$?
[ "$rc" = 2 ] && [ "$(wc -l <"$TMP/err")" = 1 ] && ok "reconstruct > /dev/full: exit 2, one line" || notok "reconstruct > /dev/full: exit $rc $(cat "$TMP/err")"
[ "$(cat "$TMP/o/old.exr")" = "keep me" ] && ok "reconstruct > /dev/full keeps old.exr" || notok "old.exr changed"
no_tmp "$TMP/o" && ok "reconstruct > /dev/full leaves no temporary" || notok "temporary left: $(ls "$TMP/o")"
"$SHLAB" reconstruct --order 2 --coeffs 1,0.5,0,0 --width 16 --out "$TMP/o/new.exr" >/dev/full 2>/dev/null
[ ! -e "$TMP/o/new.exr" ] && ok "reconstruct > /dev/full writes no new file" || notok "new.exr written"
expect_success "reconstruct replaces old.exr on success" reconstruct --order 2 --coeffs 1,0.5,0,0 --width 16 --out "$TMP/o/old.exr"
[ "$(head -c 4 "$TMP/o/old.exr" | od -An -tx1 | tr -d ' ')" = 762f3101 ] && ok "old.exr is now an EXR" || notok "old.exr not replaced"

"$SHLAB" verify --fixture $FX/orders_1_10.json --method ivanic --emit-candidate "$TMP/o/e.json" >/dev/full 2>"$TMP/err"; rc=$?
[ "$rc" = 2 ] && [ ! -e "$TMP/o/e.json" ] && no_tmp "$TMP/o" && ok "verify --emit-candidate > /dev/full leaves nothing" || notok "verify > /dev/full: exit $rc, $(ls "$TMP/o")"
printf 'old candidate' >"$TMP/o/e.json"
"$SHLAB" verify --fixture $FX/orders_1_10.json --method ivanic --emit-candidate "$TMP/o/e.json" >/dev/full 2>/dev/null
[ "$(cat "$TMP/o/e.json")" = "old candidate" ] && ok "verify > /dev/full keeps an existing candidate" || notok "e.json changed"
expect_usage_error "verify --emit-candidate into a directory" verify --fixture $FX/orders_1_10.json --method ivanic --emit-candidate "$TMP/o"

mkdir -p "$TMP/fx"
"$SHLAB" fixtures --method ivanic --out "$TMP/fx" --quiet >/dev/full 2>"$TMP/err"; rc=$?
[ "$rc" = 2 ] && [ -z "$(ls -A "$TMP/fx")" ] && ok "fixtures > /dev/full leaves the directory empty" || notok "fixtures > /dev/full: exit $rc, $(ls "$TMP/fx")"
mkdir -p "$TMP/fx/bands_50_200.json"
"$SHLAB" fixtures --out "$TMP/fx" >"$TMP/out" 2>"$TMP/err"; rc=$?
[ "$rc" = 2 ] && [ "$(wc -l <"$TMP/err")" = 1 ] && [ ! -e "$TMP/fx/orders_1_10.json" ] && no_tmp "$TMP/fx" \
    && ok "fixtures with an unwritable second file: one line, nothing written" || notok "fixtures: exit $rc, $(cat "$TMP/err"), $(ls "$TMP/fx")"
expect_usage_error "fixtures --out a missing directory (no progress first)" fixtures --out "$TMP/none/dir"

# ---- signals: temporaries removed, the process dies by the signal
mkdir -p "$TMP/sig"
"$SHLAB" fixtures --out "$TMP/sig" --quiet >/dev/null 2>&1 &
pid=$!
i=0
while [ -z "$(find "$TMP/sig" -name '*.tmp.*')" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
[ -n "$(find "$TMP/sig" -name '*.tmp.*')" ] && ok "fixtures has its temporaries open while computing" || notok "no temporary seen"
kill -TERM $pid; wait $pid; rc=$?
[ "$rc" = 143 ] && ok "SIGTERM: exit by the signal" || notok "SIGTERM: exit $rc"
[ -z "$(ls -A "$TMP/sig")" ] && ok "SIGTERM: temporaries removed" || notok "SIGTERM left: $(ls -A "$TMP/sig")"
# (a background job of a script starts with SIGINT ignored, which shlab
# respects: perl restores the default before starting it)
perl -e '$SIG{INT} = "DEFAULT"; exec @ARGV or exit 127' "$SHLAB" fixtures --out "$TMP/sig" --quiet >/dev/null 2>&1 &
pid=$!
i=0
while [ -z "$(find "$TMP/sig" -name '*.tmp.*')" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
kill -INT $pid; wait $pid; rc=$?
[ "$rc" = 130 ] && [ -z "$(ls -A "$TMP/sig")" ] && ok "SIGINT: temporaries removed, exit by the signal" || notok "SIGINT: exit $rc, left $(ls -A "$TMP/sig")"

# ---- fixture integers and empty case lists
printf '{"format":"shlab-rotation-fixtures/1","cases":[]}' >"$TMP/empty.json"
expect_usage_error "verify a fixture with no cases" verify --fixture "$TMP/empty.json" --method ivanic
for big in 2147483648 4294967297 -4294967295; do
    sed "s/\"order\":1,/\"order\":$big,/" $SEEDS/fixture/orders_1_3.json >"$TMP/big.json"
    expect_usage_error "fixture order $big" verify --fixture "$TMP/big.json" --method ivanic
done
sed 's/"id":"o2-/"id":"o1-/' $SEEDS/fixture/orders_1_3.json >"$TMP/dup.json"
expect_usage_error "fixture with a repeated case id" verify --fixture "$TMP/dup.json" --method ivanic
expect_usage_error "verify a missing fixture" verify --fixture "$TMP/none.json" --method ivanic
grep -q "line -1" "$TMP/err" && notok "missing file reported with a line number" || ok "missing file: no line number"

# ---- a repeated option is an error in every command
expect_usage_error "repeated --order" eval --order 2 --order 3 --theta 0 --phi 0
expect_usage_error "repeated --out" reconstruct --order 2 --coeffs 1,0,0,0 --out "$TMP/a.exr" --out "$TMP/b.exr"
[ ! -e "$TMP/a.exr" ] && [ ! -e "$TMP/b.exr" ] && ok "repeated --out writes nothing" || notok "repeated --out wrote a file"
expect_usage_error "repeated --light" project --order 2 --light green --light green
expect_usage_error "repeated flag --degrees" eval --order 2 --theta 0 --phi 0 --degrees --degrees
expect_usage_error "repeated --format" rotmat --order 2 --method ivanic --euler 0,0,0 --format json --format csv
grep -q "given twice" "$TMP/err" && ok "the error says 'given twice'" || notok "repeat message: $(cat "$TMP/err")"

# ---- numbers that underflow or overflow are errors, in arguments and files
expect_usage_error "cap:1e-400" project --order 2 --light cap:1e-400
expect_usage_error "--coeffs with 1e-400" reconstruct --order 2 --coeffs 1,1e-400,0,0 --out "$TMP/u.exr"
printf '{"coeffs":[1,1e-400,0,0]}' >"$TMP/u.json"
expect_usage_error "JSON coefficient 1e-400" convert --order 2 --in "$TMP/u.json" --from cs --to nocs
expect_usage_error "--theta 1e999" eval --order 2 --theta 1e999 --phi 0
expect_success "an exact zero with a tiny exponent is fine" project --order 2 --light cap:0e-400

# ---- messages that quote input stay one line
expect_usage_error "newline in an argument" eval --order "$(printf 'x\ny')" --theta 0 --phi 0
grep -q 'x\\ny' "$TMP/err" && ok "newline shown as \\n" || notok "escape: $(cat "$TMP/err")"
printf '{"format":"shlab-rotation-fixtures/1",\n"cases":[\n' >"$TMP/trunc.json"
expect_usage_error "JSON truncated after a newline" verify --fixture "$TMP/trunc.json" --method ivanic
expect_usage_error "escape and control bytes in a light spec" project --order 2 --light "$(printf 'cap:\033[31m\t1')"
expect_usage_error "invalid UTF-8 in an option value" eval --order "$(printf '\377\376')" --theta 0 --phi 0
grep -q '\\xff\\xfe' "$TMP/err" && ok "invalid UTF-8 shown as \\xNN" || notok "utf8: $(cat "$TMP/err")"
