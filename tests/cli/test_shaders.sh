#!/bin/sh
# Shader kernels (docs/check-your-kernel.md, "Shaders"; tests/shaders/):
# `verify --shader` compiles GLSL and HLSL with shaderc's library, runs every
# fixture case on the Vulkan device (lavapipe where there is no GPU) and
# judges at float32; the example shaders — the Ivanic-Ruedenberg recurrence
# written independently of shlab, so their passing checks both — pass orders
# 1-10 in both languages and every rotation input, each deliberate mistake is
# diagnosed by name as the simulated candidate's, and a shader that does not
# compile, does not finish or names a missing device is reported in one line.
# Without Vulkan the whole script is one skip line.
. tests/cli/lib.inc
FX=data/fixtures/rotation/orders_1_10.json
SH=tests/shaders

"$SHLAB" verify --quiet --fixture $FX --shader $SH/rotate_ivanic.glsl --abi matrix --orders 1 >"$TMP/out" 2>"$TMP/err"; rc=$?
if grep -q "built without Vulkan\|no device\|no Vulkan driver\|Vulkan: " "$TMP/err"; then
    ok "# skip shader tests: $(head -1 "$TMP/err")"
    exit 0
fi

field() { sed -n "s/.*\"$2\":\(\"\([^\"]*\)\"\|\([^,}]*\)\).*/\2\3/p" "$1"; }
ncs=$(grep -c '"convention":"cs"' $FX)

# Under the sanitizers (make check SANITIZE=1) the shader's own numerics run
# in lavapipe's uninstrumented code at a tenth of the speed: the host side is
# driven by one kernel per language and the mistakes that need an input of
# their own; the plain check runs every combination.
quick=0
[ "${SANITIZE:-0}" = 1 ] && quick=1

# the correct kernels: GLSL and HLSL, every rotation input, all cs cases
kernels="rotate_ivanic.glsl:matrix rotate_ivanic.glsl:quat rotate_ivanic.glsl:euler rotate_ivanic.hlsl:matrix rotate_ivanic.hlsl:euler"
[ "$quick" = 1 ] && kernels="rotate_ivanic.glsl:quat rotate_ivanic.hlsl:matrix"
for f in $kernels; do
    file=${f%%:*}; abi=${f#*:}
    "$SHLAB" verify --quiet --fixture $FX --shader "$SH/$file" --abi $abi --format json >"$TMP/p.json" 2>"$TMP/err"; rc=$?
    run=$(( $(field "$TMP/p.json" cases) - $(field "$TMP/p.json" skipped) ))
    if [ "$rc" = 0 ] && [ "$(field "$TMP/p.json" tolerance_kind)" = float32 ] && [ "$run" = "$ncs" ] &&
       [ -n "$(field "$TMP/p.json" device)" ]; then
        ok "$file ($abi): the $run cs cases pass at float32 on '$(field "$TMP/p.json" device)'"
    else notok "$file ($abi): exit $rc $(head -c 300 "$TMP/p.json") $(head -c 200 "$TMP/err")"; fi
done

# each deliberate mistake, diagnosed as the simulated candidate with that
# mistake is (float32 outputs: judged at the float32 tolerance)
mistakes="INVERSE:matrix:inverse CONVENTION:matrix:convention SWAP:euler:swap DEG2RAD:euler:deg2rad MDESC:matrix:mdesc"
[ "$quick" = 1 ] && mistakes="INVERSE:matrix:inverse SWAP:euler:swap"
for ms in $mistakes; do
    def=MISTAKE_${ms%%:*}; rest=${ms#*:}; abi=${rest%%:*}; sim=${rest#*:}
    "$SHLAB" verify --quiet --fixture $FX --method wigner --convention cs --emit-candidate "$TMP/sim.json" --simulate "$sim" >/dev/null 2>&1
    "$SHLAB" verify --quiet --fixture $FX --candidate "$TMP/sim.json" --convention cs --precision float --diagnose --format json >"$TMP/s.json" 2>/dev/null
    "$SHLAB" verify --quiet --fixture $FX --shader $SH/rotate_ivanic.glsl --abi $abi --define $def --diagnose --format json >"$TMP/p.json" 2>/dev/null; rc=$?
    want=$(field "$TMP/s.json" diagnosis); got=$(field "$TMP/p.json" diagnosis)
    if [ "$rc" = 1 ] && [ -n "$want" ] && [ "$got" = "$want" ]; then ok "--define $def: diagnosed '$got'"
    else notok "--define $def: exit $rc, shader '$got', simulated '$want'"; fi
done

# orders the shader declines (status 1) are not run
"$SHLAB" verify --quiet --fixture data/fixtures/rotation/bands_50_200.json --shader $SH/rotate_ivanic.glsl --abi matrix --format json >"$TMP/p.json" 2>"$TMP/err"; rc=$?
if [ "$rc" = 2 ] && grep -q "declined every case" "$TMP/err"; then ok "bands 50 and 200: declined (status 1), refused as nothing to judge"; else notok "bands: exit $rc $(cat "$TMP/err")"; fi

# misbehaviour: one line each
expect_refused "a shader that does not compile" "does not compile: .*rotate_ivanic.glsl:[0-9]+: error" verify --fixture $FX --shader $SH/rotate_ivanic.glsl --abi matrix --define BROKEN
expect_refused "--device beyond the machine's" "device 63: this machine has" verify --fixture $FX --shader $SH/rotate_ivanic.glsl --abi matrix --device 63
expect_refused "--abi of a plug-in given to a shader" "unknown shader input" verify --fixture $FX --shader $SH/rotate_ivanic.glsl --abi matrix-d
printf 'not SPIR-V at all' >"$TMP/x.spv"
expect_refused "a .spv that is not SPIR-V" "not SPIR-V" verify --fixture $FX --shader "$TMP/x.spv" --abi matrix
expect_refused "--define without --shader" "apply to --shader" verify --fixture $FX --method zxzxz --define X
"$SHLAB" verify --quiet --fixture $FX --shader $SH/rotate_ivanic.glsl --abi matrix --define HANG_ORDER_3 --timeout 0.5 --format json >"$TMP/p.json" 2>"$TMP/err"; rc=$?
if [ "$rc" = 1 ] && grep -q "^verify: the shader did not finish within 0.5 s, on the dispatch of order 3" "$TMP/err" &&
   [ "$(field "$TMP/p.json" failed)" = 0 ]; then
    ok "a shader that does not finish: stopped after 0.5 s at order 3, the orders before judged"
else notok "hang: exit $rc $(head -c 300 "$TMP/err") $(head -c 300 "$TMP/p.json")"; fi

# SPIR-V as is: the same verdict as its source
if command -v glslc >/dev/null 2>&1 && glslc -fshader-stage=compute -o "$TMP/k.spv" $SH/rotate_ivanic.glsl 2>/dev/null; then
    expect_success "a .spv compiled by glslc passes" verify --quiet --fixture $FX --shader "$TMP/k.spv" --abi matrix
else ok "# skip .spv check: no glslc"; fi

# bench --shader: the device named, CPU figures said to be so on lavapipe,
# one row per K with both times; no timing is asserted
"$SHLAB" bench --quiet --shader $SH/rotate_ivanic.glsl --abi matrix --order 3 --count 1,256 --repeat 3 --target-ms 1 --format json >"$TMP/b.json" 2>"$TMP/err"; rc=$?
rows=$(grep -o '"k":' "$TMP/b.json" | wc -l)
if [ "$rc" = 0 ] && [ "$rows" = 2 ] && [ -n "$(field "$TMP/b.json" device)" ] &&
   { [ "$(field "$TMP/b.json" device_is_cpu)" = false ] || grep -q '"note":"a CPU device (lavapipe): the shader' "$TMP/b.json"; }; then
    ok "bench --shader: 2 rows on '$(field "$TMP/b.json" device)', CPU device said so"
else notok "bench --shader: exit $rc $(head -c 400 "$TMP/b.json") $(head -c 200 "$TMP/err")"; fi
for f in shader_ns_per_rotation cpu_ns_per_rotation ratio; do
    v=$(field "$TMP/b.json" $f)
    if awk -v x="$v" 'BEGIN { exit !(x > 0) }'; then ok "bench --shader: $f = $v > 0"; else notok "bench --shader: $f '$v'"; fi
done
expect_refused "bench --shader without --abi" "needs --abi" bench --shader $SH/rotate_ivanic.glsl
expect_refused "bench --shader, K beyond 2^20" "count" bench --shader $SH/rotate_ivanic.glsl --abi matrix --count 2000000
"$SHLAB" bench --quiet --shader $SH/rotate_ivanic.glsl --abi matrix --order 12 --count 4 --repeat 3 >"$TMP/out" 2>"$TMP/err"; rc=$?
if [ "$rc" = 2 ] && grep -q "does not rotate this order" "$TMP/err"; then ok "bench --shader at an order the shader declines: one line"; else notok "bench declined order: exit $rc $(cat "$TMP/err")"; fi
# the top of --count (2^20 rotations in one dispatch): every output of the
# first dispatch against shlab's exact rotation in double (a second method:
# zxzxz from the same matrices), for shlab's generated shader; and a shader
# with a mistake is seen to be wrong there (the check bites)
if [ "$quick" = 0 ]; then
    "$SHLAB" bench --quiet --shader data/shaders/rot_zxzxz.glsl --abi matrix --order 2 --count 1048576 --repeat 3 --target-ms 1 --format json >"$TMP/b.json" 2>"$TMP/err"; rc=$?
    e=$(field "$TMP/b.json" max_error)
    if [ "$rc" = 0 ] && awk -v e="$e" 'BEGIN { exit !(e <= 2e-6) }'; then ok "bench --shader at K = 2^20: all 1048576 outputs within 2e-6 of the exact rotation (max $e)"
    else notok "bench --shader at K = 2^20: exit $rc, max_error '$e' $(head -c 200 "$TMP/err")"; fi
fi
"$SHLAB" bench --quiet --shader $SH/rotate_ivanic.glsl --define MISTAKE_INVERSE --abi matrix --order 3 --count 256 --repeat 3 --target-ms 1 --format json >"$TMP/b.json" 2>/dev/null
e=$(field "$TMP/b.json" max_error)
if awk -v e="$e" 'BEGIN { exit !(e > 1e-2) }'; then ok "bench --shader: a shader with a mistake shows max_error $e"; else notok "bench --shader mistake: max_error '$e'"; fi
