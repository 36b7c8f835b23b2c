#!/bin/sh
# make_seeds.sh — (re)write the seed corpus in tests/fuzz/corpus/ (kept in
# the repository: make check replays it, make fuzz starts from it).
# Usage: tests/fuzz/make_seeds.sh [BUILD]   (BUILD: build dir with exr_writer.o)
set -eu
cd "$(dirname "$0")/../.."
B=${1:-build}
C=tests/fuzz/corpus
mkdir -p $C/exr $C/fixture $C/candidate $C/coeffs $C/light $C/rotation $C/mesh $C/merge

# exr: written by OpenEXR's C++ library
make -s "$B/tests/exr_writer.o"
cc -std=c11 -O1 -Itests -Isrc $(pkg-config --cflags OpenEXR) -o "$B/exr_seeds" tests/fuzz/exr_seeds.c \
   "$B/tests/exr_writer.o" $(pkg-config --libs OpenEXR) -lstdc++
"$B/exr_seeds" $C/exr
# two small files whose headers claim 32768×32768 pixels (dataWindow, and for
# the tiled one a single 32768×32768 tile): refused before any allocation
perl -0777 -pe 's/(dataWindow\0box2i\0\x10\0\0\0).{16}/$1.pack("l<4",0,0,32767,32767)/se' \
    $C/exr/rgba-half-scan-zip.exr > $C/exr/huge-window-scan.exr
perl -0777 -pe 's/(dataWindow\0box2i\0\x10\0\0\0).{16}/$1.pack("l<4",0,0,32767,32767)/se;
               s/(tiles\0tiledesc\0\x09\0\0\0).{8}/$1.pack("L<2",32768,32768)/se' \
    $C/exr/rgb-float-tiled-zip.exr > $C/exr/huge-window-tile.exr
# the same at 8192×8192 (SH_IMAGE_MAX_PIXELS): past the pixel count, refused by
# the chunk table's size and by the compression ratio
perl -0777 -pe 's/(dataWindow\0box2i\0\x10\0\0\0).{16}/$1.pack("l<4",0,0,8191,8191)/se' \
    $C/exr/rgba-half-scan-zip.exr > $C/exr/huge-window-8k-scan.exr
perl -0777 -pe 's/(dataWindow\0box2i\0\x10\0\0\0).{16}/$1.pack("l<4",0,0,8191,8191)/se;
               s/(tiles\0tiledesc\0\x09\0\0\0).{8}/$1.pack("L<2",8192,8192)/se' \
    $C/exr/rgb-float-tiled-zip.exr > $C/exr/huge-window-8k-tile.exr

# fixture: the first cases of the golden fixtures, and broken variants
F=data/fixtures/rotation/orders_1_10.json
{ sed -n '1,3p' $F; sed -n '4,6p' $F | sed '$ s/,$//'; echo ']}'; } > $C/fixture/orders_1_3.json
{ sed -n '1,3p' data/fixtures/rotation/bands_50_200.json; sed -n '4p' data/fixtures/rotation/bands_50_200.json | sed 's/,$//'; echo ']}'; } > $C/fixture/band_50.json
printf '{"format":"shlab-rotation-fixtures/1","cases":[]}' > $C/fixture/empty.json
sed 's/"order":1,/"order":4294967297,/' $C/fixture/orders_1_3.json > $C/fixture/order_2p32.json
sed 's/"order":2,/"order":2147483648,/' $C/fixture/orders_1_3.json > $C/fixture/order_2p31.json
head -c 300 $C/fixture/orders_1_3.json > $C/fixture/truncated.json

# candidate: for the fixture built into fuzz_candidate.c
printf '{"results":{"o3":[1,0,0,0,0,0,0,0,0],\n"b2":[0,0,1,0,0],\n"\\u00e91":[2]}}\n' > $C/candidate/good.json
printf '{"results":{"o3":[1,0,0,0,0,0,0,0,0],"b2":[0,0,1,0]}}\n' > $C/candidate/short.json
printf '{"results":{"o3":[1,0,0,0,0,0,0,0,1e-400],"b2":[0,0,1,0,0],"\\u00e91":[2]}}\n' > $C/candidate/underflow.json
printf '{"results":{"o3":"x"}}' > $C/candidate/not_numbers.json

# coeffs
printf '1 0.5 0 0\n' > $C/coeffs/text.txt
printf '[1, 0.5, -0.25, 0.125, 0, 0, 0, 0, 0.1]\n' > $C/coeffs/brackets.txt
printf '{"coeffs":[1,0.5,0,0]}' > $C/coeffs/coeffs.json
printf '{"channels":{"R":[1,0,0,0],"G":[0.5,0,0,0],"B":[0.25,0,0,0]}}' > $C/coeffs/channels.json
printf '{"channels":{"R":[1,0,0,0],"G":[0.5,0,0]}}' > $C/coeffs/unequal.json
printf '{"coeffs":[1,1e-400,0,0]}' > $C/coeffs/underflow.json

# light and the other text specs: first byte = parser (and flags), then the spec
i=0
for spec in '\000green' '\000cap:0.5' '\020cap:90' '\000cie-overcast' '\000cie-clear:0.3,1' \
            '\001cie-partly:1.5,2' '\040const:2' '\140lobe:3.5' '\000cap:1e-400' \
            '\002gauss:0.01' '\002hann:4' '\002lanczos' '\002none' '\003quad' '\003mc' \
            '\004ivanic' '\004taylor1.5' '\005float' '\006nocs' '\0074pi' '\007schmidt' \
            '\010latlong' '\010probe' '\011cone' '\012lobe' '\013uniform' '\053cubic' '\013sphere'; do
    printf "$spec" > $C/light/spec_$i
    i=$((i + 1))
done

# rotation: lines "<letter><value>" (see fuzz_rotation.c)
printf 'e0.1,0.2,0.3\nO4\nMivanic\n' > $C/rotation/euler
printf 'e30,60,-45\nd\nO5\nMzxzxz\nCnocs\n' > $C/rotation/euler_degrees
printf 'q1,0,0,0\nO3\nMwigner\ni\n' > $C/rotation/quat
printf 'm0,-1,0,1,0,0,0,0,1\no\nO4\nMchoi\n' > $C/rotation/matrix
printf 'a0,0,1\nA1.5\nO6\nMblanco\nPfloat\n' > $C/rotation/axis_angle
printf 'e0,0,0.7\nO3\nMz\n' > $C/rotation/z
printf 'e0.1,0.05,0.2\nO4\nMtaylor1.5\n' > $C/rotation/taylor
printf 'n1,2,3 4 [5]\nn1e-400\n' > $C/rotation/numbers
# found by fuzzing: an axis 1e-150 away from z (β ≈ 1e-150), band 7 by blanco's
# single-band recurrence was NaN
printf 'a0,1e-150,1\nA.5\nO8\nMblanco\n' > $C/rotation/blanco_tiny_beta
# mesh: the good and hostile files of mesh_files.pl, small cuts of the test
# models (with `make models`: data/models is not in the repository), and one
# frame of the importer's protocol (fuzz_mesh.c reads those apart by magic)
perl tests/fuzz/mesh_files.pl $C/mesh
M=data/models
if [ -f $M/Wuson.ply ] && [ -f $M/WusonOBJ.obj ] && [ -f $M/spider.obj ]; then
    # Wuson.ply: the header with 60 vertices and their 20 faces (face i uses 3i..3i+2)
    awk '/^element vertex/ { $3 = 60 } /^element face/ { $3 = 20 } { print } /^end_header/ { exit }' $M/Wuson.ply >$C/mesh/wuson-60.ply
    awk 'h && v < 60 { print; v++ } /^end_header/ { h = 1 }' $M/Wuson.ply >>$C/mesh/wuson-60.ply
    grep -n '' $M/Wuson.ply | awk -F: '$1 > 15 + 11184 && $1 <= 15 + 11184 + 20 { sub(/^[0-9]*:/, ""); print }' >>$C/mesh/wuson-60.ply
    head -c 200 $M/Wuson.ply >$C/mesh/bad-wuson-header-cut.ply
    head -c 2000 $C/mesh/wuson-60.ply >$C/mesh/bad-wuson-body-cut.ply
    # the OBJ models: the first 40 of each kind of element, the statements using only those
    for o in WusonOBJ spider; do
        awk -v K=40 '
            /^v / { if (++nv > K) next } /^vt / { if (++nt > K) next } /^vn / { if (++nn > K) next }
            /^f / { for (i = 2; i <= NF; i++) { split($i, c, "/"); for (j in c) if (c[j] + 0 > K) next } }
            { print }' $M/$o.obj >$C/mesh/$(echo $o | tr 'A-Z' 'a-z')-40.obj
    done
else
    echo "make_seeds: no data/models (make models): the mesh seeds lack the cuts of the test models" >&2
fi
# a frame: one triangle (0,0,0) (1,0,0) (0,1,0), no normals (mesh_internal.h)
perl -e 'print "SHMESH\x01\n", pack("L l q q l l l L", 1, 0, 3, 1, 0, 1, 0, 0),
         pack("d9", 0, 0, 0, 1, 0, 0, 0, 1, 0), pack("l3", 0, 1, 2), "SHMESH-E", pack("Q", 84)' >$C/mesh/frame-triangle
# merge: shard files written by the sweeps' --shard (small sweeps), the files
# of one input separated by the byte 0x1e (see fuzz_merge.c); then damaged
# variants, each of which merge must refuse in one line
make -s "$B/shlab"
M=$C/merge
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
join_files() { out=$1; shift; first=1; for f in "$@"; do [ $first = 1 ] || printf '\036'; cat "$f"; first=0; done > "$out"; }
for i in 0 1; do
    "$B/shlab" stability --method zxzxz --lmax 6 --ref-max 2 --shard $i/2 > "$T/stab$i" 2>/dev/null
    "$B/shlab" taylor-error --order 4 --taylor 1.5 --beta-max 30 --steps 5 --degrees --format csv --shard $i/2 > "$T/te$i" 2>/dev/null
    "$B/shlab" scale-interp --order 3 --family midrange --samples 4 --spacing uniform --kmin -0.5 --kmax 0.6 --dense 6 \
        --interp cubic --format json --shard $i/2 > "$T/si$i" 2>/dev/null
    "$B/shlab" plan --order 2 --max-beta 6 --degrees --quiet --tolerance 1e-3 --shard $i/2 > "$T/pl$i" 2>/dev/null
done
for i in 0 1 2; do
    "$B/shlab" stability --method ivanic --bands 2,5,9,14,16,18 --ref-max -1 --stop-above 3e-15 --shard $i/3 > "$T/stop$i" 2>/dev/null
done
"$B/shlab" taylor-error --order 3 --taylor 2 --beta 0.5 --shard 0/1 > "$T/one" 2>/dev/null
join_files $M/stability "$T/stab0" "$T/stab1"
join_files $M/stability_reversed "$T/stab1" "$T/stab0"
join_files $M/taylor_error "$T/te0" "$T/te1"
join_files $M/scale_interp "$T/si1" "$T/si0"
join_files $M/plan "$T/pl0" "$T/pl1"
join_files $M/stopped "$T/stop0" "$T/stop1" "$T/stop2"
cp "$T/one" $M/one_shard
# damaged rows and lines (the issue's list, and their neighbours)
sed 's/"band":3/"band":5/' "$T/stab0" > "$T/x"; join_files $M/bad_band_relabelled "$T/x" "$T/stab1"
sed 's/"orth":\([-0-9.e]*\),"orth_exact":true,"hom":\([-0-9.e]*\),"ref":null/"orth":"x","orth_exact":true,"hom":\2,"ref":null/' "$T/stab0" > "$T/x"
join_files $M/bad_orth_string "$T/x" "$T/stab1"
sed 's/,"hom":[-0-9.e]*//' "$T/stab1" > "$T/x"; join_files $M/bad_missing_field "$T/stab0" "$T/x"
sed 's/"broken":false}}/"broken":false,"extra":1}}/' "$T/stab1" > "$T/x"; join_files $M/bad_extra_field "$T/stab0" "$T/x"
perl -pe 's/\}\}$/}}\0junk/ if $. == 2' "$T/stab0" > "$T/x"; join_files $M/bad_nul_in_line "$T/x" "$T/stab1"
sed 's/{"end":{"rows":[0-9]*,"stopped":false}}/{"end":{}}/' "$T/te0" > "$T/x"; join_files $M/bad_end_empty "$T/x" "$T/te1"
sed 's/"k":\([-0-9]*\)\.[0-9]*/"k":\1/' "$T/si0" > "$T/x"; join_files $M/bad_integer_for_real "$T/x" "$T/si1"
sed 's/"item":1,/"item":99,/' "$T/te1" > "$T/x"; join_files $M/bad_item_range "$T/te0" "$T/x"
sed 's/"beta":0.0,/"beta":0.0,"beta":1.0,/' "$T/te0" > "$T/x"; join_files $M/bad_duplicate_key "$T/x" "$T/te1"
sed 's/"errors":\[[-0-9.e]*,/"errors":[/' "$T/pl1" > "$T/x"; join_files $M/bad_errors_short "$T/pl0" "$T/x"
sed 's/"lmax":6/"lmax":"6"/' "$T/stab0" > "$T/x"; sed 's/"lmax":6/"lmax":"6"/' "$T/stab1" > "$T/y"; join_files $M/bad_params_type "$T/x" "$T/y"
{ cat "$T/te0"; echo '{"end":{"rows":0,"stopped":false}}'; } > "$T/x"; join_files $M/bad_text_after_end "$T/x" "$T/te1"
head -1 "$T/stab0" > $M/bad_header_only
printf '{"shlab_shard":{"command":"stability"}}\n' > $M/bad_header_fields
echo "make_seeds: $(find $C -type f | wc -l) files in $C"
