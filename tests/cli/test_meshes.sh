#!/bin/sh
# test_meshes.sh — hostile mesh files through the commands that read one:
# each is refused with exit 2 and exactly one line "shlab: error: cannot read
# mesh 'F': ..." within 2 s, writing nothing (under make check SANITIZE=1 a
# sanitizer or leak report would add lines and change the exit status); good
# meshes load with the content their construction gives them.  The files come
# from tests/fuzz/mesh_files.pl (its header says what each is), plus two cuts
# of the test model data/models/Wuson.ply when `make models` has run.
. "$(dirname "$0")/lib.inc"
D="$TMP/m"
O="$TMP/out"
mkdir -p "$O"
if ! perl tests/fuzz/mesh_files.pl "$D"; then notok "tests/fuzz/mesh_files.pl wrote the files"; exit 0; fi
if [ -f data/models/Wuson.ply ]; then
    head -c 457877 data/models/Wuson.ply >"$D/bad-wuson-body-cut.ply"   # assimp aborted
    head -c 200 data/models/Wuson.ply >"$D/bad-wuson-header-cut.ply"    # assimp read forever
else
    echo "SKIP Wuson cuts: no data/models/Wuson.ply (make models)"
fi

ms_now() { date +%s%N | cut -b1-13; }
# refused FILE CMD...: exit 2, stdout empty, one stderr line naming FILE, < LIMIT ms (2 s), nothing in $O
LIMIT=2000
refused() {
    f=$1; shift
    t0=$(ms_now)
    "$SHLAB" "$@" --mesh "$f" >"$TMP/o" 2>"$TMP/e"; rc=$?
    ms=$(($(ms_now) - t0))
    what="$1 $(basename "$f")"
    if [ "$rc" = 2 ] && [ ! -s "$TMP/o" ] && [ "$(wc -l <"$TMP/e")" = 1 ] &&
        grep -qF "shlab: error: cannot read mesh '$f': " "$TMP/e" && [ "$ms" -lt "$LIMIT" ] && [ -z "$(ls -A "$O")" ]; then
        ok "$what: refused in $ms ms"
    else
        notok "$what: exit $rc in $ms ms, stdout $(wc -c <"$TMP/o") bytes, files [$(ls -A "$O")], stderr: $(head -c 300 "$TMP/e")"
        rm -f "$O"/* "$O"/.[!.]* 2>/dev/null
    fi
}

for f in "$D"/bad-*; do refused "$f" transfer --rays 16; done
# the other readers, on the three kinds of failure (importer abort, endless
# read, allocation storm before the guard)
for f in "$D/bad-ply-count-short.ply" "$D/bad-ply-header-cut.ply" "$D/bad-ply-binary-count-2e9.ply"; do
    refused "$f" render --light const:1 --rays 16 --width 8 --height 8 --out "$O/r.exr" --png "$O/r.png"
    refused "$f" scene-plan --light const:1 --budget 0.1 --rays 16
    refused "$f" cache --light const:1 --png "$O/c.png"
done

# a format the guard does not read (OFF) claiming 2e8 vertices: the sandbox
# alone stops the importer's 2.4 GB allocation (a memory limit of 1 GB and
# more; AddressSanitizer poisons the allocation's shadow first: allow 10 s)
printf 'OFF\n200000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >"$D/bad-off-2e8.off"
LIMIT=10000
refused "$D/bad-off-2e8.off" transfer --rays 16
LIMIT=2000

# the importer's child dies with shlab: SIGTERM to shlab while the child
# triangulates one convex face of 16000 corners (within the guard's budget,
# some seconds of work); then neither process may be left
perl -e 'for $i (0 .. 15999) { $a = 6.283185307 * $i / 16000; printf "v %.9f %.9f 0\n", cos($a), sin($a) }
         print "f ", join(" ", 1 .. 16000), "\n"' >"$D/slow-poly.obj"
procs() { grep -la 'slow-pol[y]\.obj' /proc/[0-9]*/cmdline 2>/dev/null; } # (the bracket: not grep itself)
"$SHLAB" transfer --mesh "$D/slow-poly.obj" --rays 4 --quiet >/dev/null 2>&1 &
pid=$!
i=0
while [ "$(procs | wc -l)" -lt 2 ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i + 1)); done
seen=$(procs | wc -l)
kill -TERM $pid
wait $pid; rc=$?
i=0
while [ -n "$(procs)" ] && [ $i -lt 20 ]; do sleep 0.05; i=$((i + 1)); done
if [ "$seen" = 2 ] && [ "$rc" = 143 ] && [ -z "$(procs)" ]; then ok "SIGTERM during the import: shlab and its importer gone"
else notok "SIGTERM during the import: $seen processes seen, exit $rc, left: $(procs)"; fi

# the reason names what is wrong, and where: reason FILE TEXT
reason() {
    "$SHLAB" transfer --mesh "$D/$1" 2>"$TMP/e" >/dev/null
    if grep -qF "$2" "$TMP/e"; then ok "$1: names '$2'"; else notok "$1: '$2' not in: $(cat "$TMP/e")"; fi
}
reason bad-obj-nan-late.obj "OBJ vertex 4 (line 4) has a non-finite coordinate 'nan'"
reason bad-obj-inf-unused.obj "OBJ vertex 4 (line 4) has a non-finite coordinate 'inf'"
reason bad-obj-1e308.obj "a coordinate out of range: '1e308' (|x| <= 1e+38)"
reason bad-ply-nan-late.ply "PLY vertex 3 (line 14) has a non-finite coordinate 'nan'"
reason bad-ply-ascii-count-20digits.ply "element 'vertex' has 99999999999999999999 instances, more than the 67108864"
reason bad-ply-list-count-zero.ply "PLY face 0 has no vertex indices"
reason bad-off-2e8.off "memory limit"

# good files: vertices and triangles as built (mesh_files.pl): the square 4
# and 2 in every encoding, the quad 4 and 2, the cube 24 corners (8 corners ×
# 3 face normals) and 12, the 12 × 12 grid 13² and 2·12²
for g in square.obj:4:2 square-crlf.obj:4:2 square-ascii.ply:4:2 square-le.ply:4:2 square-be.ply:4:2 \
         quad-le.ply:4:2 cube.obj:24:12 grid-ascii.ply:169:288; do
    f="$D/good-${g%%:*}"; nv=$(echo "$g" | cut -d: -f2); nt=$(echo "$g" | cut -d: -f3)
    if "$SHLAB" transfer --mesh "$f" --rays 16 --quiet --format json >"$TMP/o" 2>"$TMP/e" &&
        grep -q "\"vertices\":$nv,\"triangles\":$nt," "$TMP/o"; then
        ok "good-${g%%:*}: $nv vertices, $nt triangles"
    else
        notok "good-${g%%:*}: expected $nv vertices, $nt triangles: $(head -c 200 "$TMP/o") $(head -c 200 "$TMP/e")"
    fi
done
exit 0
