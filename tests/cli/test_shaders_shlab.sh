#!/bin/sh
# shlab's own compute shaders (data/shaders/, written by
# tools/gen_rot_unrolled.c --shader) on a Vulkan device (lavapipe without a
# GPU), judged by `shlab verify --shader` at float32 against the golden
# fixtures: the exact zxzxz against orders_1_10.json (the MPFR reference);
# each Taylor kernel against the fixture whose expected values are that
# Taylor method's own double results (`shlab fixtures --method M`:
# orders_1_10_taylor1.5.json is committed, taylor1 and taylor2 are written
# here into $TMP).  Orders 1-6, each convention (cs; nocs = the shader
# compiled with SHLAB_NOCS), GLSL and HLSL, the rotation as a matrix for
# every shader; ZYZ angles for zxzxz in both languages; the quaternion and
# the Taylor kernels' angles in GLSL (the two languages share the code of
# those forms, and each run costs a compilation and a device).
# Skipped (one line) where shlab has no Vulkan or finds no device.
. tests/cli/lib.inc
FX=data/fixtures/rotation
SH=data/shaders

"$SHLAB" verify --quiet --fixture $FX/orders_1_10.json --shader $SH/rot_zxzxz.glsl --abi matrix --orders 1 \
    >"$TMP/probe" 2>"$TMP/probe.err"
if grep -Eq 'built without Vulkan|Vulkan: no device|no Vulkan driver' "$TMP/probe.err"; then
    echo "ok 1 - # skip shlab's shaders: no Vulkan ($(head -1 "$TMP/probe.err" | cut -c1-120))"
    exit 0
fi

for m in taylor1 taylor2; do
    "$SHLAB" fixtures --quiet --method $m --out "$TMP" >/dev/null 2>"$TMP/fx.err" ||
        notok "shlab fixtures --method $m: $(head -c 200 "$TMP/fx.err")"
done

# check METHOD FILE ABI CONV [EXTRA...]: passes at float32 on its orders 1-6 cases
check() {
    meth=$1; f=$2; abi=$3; conv=$4; shift 4
    case $meth in
    zxzxz) fx=$FX/orders_1_10.json ;;
    taylor1.5) fx=$FX/orders_1_10_taylor1.5.json ;;
    *) fx=$TMP/orders_1_10_$meth.json ;;
    esac
    def=""
    [ "$conv" = nocs ] && def="--define SHLAB_NOCS"
    # shellcheck disable=SC2086
    "$SHLAB" verify --quiet --fixture "$fx" --shader "$f" --abi "$abi" --convention "$conv" $def "$@" \
        --format json >"$TMP/out" 2>"$TMP/err"
    rc=$?
    if [ "$rc" = 0 ] && grep -q '"pass":true' "$TMP/out" && grep -q '"tolerance_kind":"float32"' "$TMP/out" &&
        grep -q '"failed":0,' "$TMP/out" && grep -q '"cases":200,' "$TMP/out" && grep -q '"skipped":140,' "$TMP/out"; then
        worst=$(sed -n 's/.*"worst_error":\([^,]*\),"worst_tolerance":\([^,]*\),.*/\1 of \2/p' "$TMP/out")
        ok "$f $abi $conv ($meth fixture): 60 cases pass at float32 (worst $worst)"
    else
        notok "$f $abi $conv ($meth fixture): exit $rc $(head -c 300 "$TMP/err") $(head -c 400 "$TMP/out")"
    fi
}

for pair in zxzxz:rot_zxzxz taylor1:rot_taylor1 taylor1.5:rot_taylor15 taylor2:rot_taylor2; do
    meth=${pair%%:*}; base=${pair#*:}
    for ext in glsl hlsl; do
        for conv in cs nocs; do
            check $meth $SH/$base.$ext matrix $conv --orders 1-6
        done
    done
done
for ext in glsl hlsl; do
    for conv in cs nocs; do check zxzxz $SH/rot_zxzxz.$ext euler $conv --orders 1-6; done
done
check zxzxz $SH/rot_zxzxz.glsl quat cs --orders 1-6
check zxzxz $SH/rot_zxzxz.glsl quat nocs --orders 1-6
for pair in taylor1:rot_taylor1 taylor1.5:rot_taylor15 taylor2:rot_taylor2; do
    meth=${pair%%:*}; base=${pair#*:}
    check $meth $SH/$base.glsl euler cs --orders 1-6
    check $meth $SH/$base.glsl quat cs --orders 1-6
done

# orders 7-10 are declined (status 1), not failed: all orders asked for
"$SHLAB" verify --quiet --fixture $FX/orders_1_10.json --shader $SH/rot_zxzxz.hlsl --abi matrix --convention cs \
    --format json >"$TMP/out" 2>"$TMP/err"
if grep -q '"pass":true' "$TMP/out" && grep -q '40 declined by the kernel' "$TMP/out"; then
    ok "rot_zxzxz.hlsl declines orders 7-10 (status 1): 40 cases not run, the rest pass"
else
    notok "orders 7-10: $(head -c 300 "$TMP/err") $(head -c 400 "$TMP/out")"
fi
