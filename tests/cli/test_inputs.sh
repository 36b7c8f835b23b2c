#!/bin/sh
# test_inputs.sh — the one input-file policy of every reader, and outputs that
# would overwrite an input.
#
# Inputs: a FIFO (nobody writing), a character device and a directory are
# refused by every reader with one error line, exit 2, within 2 s (a FIFO
# used to block the open forever, /dev/zero was read to 4 GB).
# Outputs: an output that names an input — the same path, a symbolic link to
# it, a hard link — is refused before anything runs, and the input is left
# byte for byte as it was.
. "$(dirname "$0")/lib.inc"

FX=data/fixtures/rotation/orders_1_10.json
mkfifo "$TMP/fifo"
mkdir "$TMP/dir"
printf '{"coeffs":[1,0,0,0]}\n' > "$TMP/c.json"
# a small lat-long probe for the probe readers
"$SHLAB" reconstruct --order 2 --coeffs 1,0,0.5,0 --width 16 --out "$TMP/p.exr" >/dev/null 2>&1

# within2 "what" args...: expect_usage_error under a 2 s limit
within2() {
    what=$1; shift
    timeout 2 "$SHLAB" "$@" >"$TMP/out" 2>"$TMP/err"; rc=$?
    lines=$(wc -l <"$TMP/err")
    if [ "$rc" = 2 ] && [ ! -s "$TMP/out" ] && [ "$lines" = 1 ] && grep -q '^shlab: error: ' "$TMP/err"; then
        ok "$what"
    else
        notok "$what (exit $rc$([ "$rc" = 124 ] && echo ': timed out'), stderr: $(head -c 200 "$TMP/err"))"
    fi
}

for bad in fifo dir dev; do
    case $bad in fifo) f="$TMP/fifo" ;; dir) f="$TMP/dir" ;; dev) f=/dev/zero ;; esac
    within2 "$bad as --mesh" transfer --mesh "$f" --rays 16
    within2 "$bad as --probe" scene-plan --scene bowl --probe "$f" --budget 0.1
    within2 "$bad as project --exr" project --order 2 --exr "$f"
    within2 "$bad as plan --exr" plan --order 4 --tolerance 1e-3 --max-beta 0.3 --exr "$f"
    within2 "$bad as merge FILE" merge "$f"
    within2 "$bad as verify --fixture" verify --fixture "$f" --method zxzxz
    within2 "$bad as verify --candidate" verify --fixture "$FX" --candidate "$f"
    within2 "$bad as rotate --in" rotate --method zxzxz --euler 0.1,0.2,0.3 --in "$f"
    within2 "$bad as reconstruct --in" reconstruct --order 2 --in "$f" --out "$TMP/r.exr"
    within2 "$bad as convert --in" convert --from cs --to nocs --in "$f"
done
within2 "a FIFO is named as such" transfer --mesh "$TMP/fifo" --rays 16
grep -q "(a FIFO)" "$TMP/err" && ok "message names the FIFO" || notok "message names the FIFO: $(cat "$TMP/err")"

# ---- outputs that name an input
cp "$FX" "$TMP/fx.json"
sum0=$(cksum <"$TMP/fx.json")
ln -s "$TMP/fx.json" "$TMP/fx_link.json"
ln "$TMP/fx.json" "$TMP/fx_hard.json"
for o in fx.json fx_link.json fx_hard.json; do
    within2 "verify --emit-candidate $o over its fixture" verify --fixture "$TMP/fx.json" --method zxzxz --emit-candidate "$TMP/$o"
done
[ "$(cksum <"$TMP/fx.json")" = "$sum0" ] && ok "the fixture is untouched" || notok "the fixture was changed"
grep -q "is also" "$TMP/err" && ok "the message says why" || notok "message: $(cat "$TMP/err")"

sum1=$(cksum <"$TMP/p.exr")
ln -s "$TMP/p.exr" "$TMP/p_link.exr"
within2 "render --out over its --probe" render --scene bowl --res 4 --probe "$TMP/p.exr" --rays 16 --width 16 --height 12 --quiet --out "$TMP/p.exr"
within2 "render --png over its --probe (link)" render --scene bowl --res 4 --probe "$TMP/p.exr" --rays 16 --width 16 --height 12 --quiet --out "$TMP/x.exr" --png "$TMP/p_link.exr"
[ "$(cksum <"$TMP/p.exr")" = "$sum1" ] && ok "the probe is untouched" || notok "the probe was changed"
[ ! -e "$TMP/x.exr" ] && ok "no other output written" || notok "an output was written although the run was refused"
within2 "reconstruct --out over its --in" reconstruct --order 2 --in "$TMP/c.json" --out "$TMP/c.json"
within2 "cache --png over its --probe" cache --scene bowl --res 4 --probe "$TMP/p.exr" --quiet --png "$TMP/p.exr"
ls "$TMP" | grep -q '\.tmp\.' && notok "temporary files left: $(ls "$TMP" | grep '\.tmp\.')" || ok "no temporary file left"
