#!/bin/sh
# shlab's own compute shaders (data/shaders/rot_*.glsl, .hlsl) are what their
# generator writes: each file's banner records its command
# (tools/gen_rot_unrolled.c --shader ...); regenerating must reproduce it
# byte for byte (`make regen` rewrites them).  Verifying them on a Vulkan
# device is tests/cli/test_shaders_shlab.sh.
. tests/cli/lib.inc
BUILD=${BUILD:-build}
GEN=$BUILD/tools/gen_rot_unrolled
want="rot_zxzxz rot_taylor1 rot_taylor15 rot_taylor2"
for b in $want; do
    for ext in glsl hlsl; do
        f=data/shaders/$b.$ext
        if [ ! -f "$f" ]; then notok "$f missing"; continue; fi
        cmd=$(sed -n "s|^//   build/tools/gen_rot_unrolled \(.*\) > $f\$|\1|p" "$f")
        if [ ! -x "$GEN" ] || [ -z "$cmd" ]; then notok "$f: generator $GEN or the command in the banner missing"; continue; fi
        # shellcheck disable=SC2086
        if "$GEN" $cmd >"$TMP/gen" 2>"$TMP/gen.err" && cmp -s "$TMP/gen" "$f"; then
            ok "$f is what 'gen_rot_unrolled $cmd' writes"
        else
            notok "$f differs from the generator's output (run make regen): $(diff "$f" "$TMP/gen" | head -5) $(head -c 200 "$TMP/gen.err")"
        fi
        if grep -q 'DO NOT EDIT' "$f"; then ok "$f: banner says DO NOT EDIT"; else notok "$f: no DO NOT EDIT banner"; fi
    done
done
# no stray generated shader without a check
n_files=$(ls data/shaders/rot_*.glsl data/shaders/rot_*.hlsl 2>/dev/null | wc -l)
if [ "$n_files" = 8 ]; then ok "data/shaders holds the 8 generated shaders"; else notok "data/shaders holds $n_files rot_* shaders, expected 8"; fi
