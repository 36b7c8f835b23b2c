#!/bin/sh
# test_readme_examples.sh — every console example in README.md and the
# manual's pages (docs/*.md, in the order the README lists them) prints
# exactly what the page shows.  A ```console block holds one or more examples: a
# line "$ COMMAND" followed by its output (stdout and stderr as a terminal
# shows them).  Each command runs in a scratch directory (with the
# repository's data/, src/ and tests/ visible, and `shlab` meaning the binary under test) and
# its output is compared with the page's: the same text, and every number
# equal to 1e-13 relative or 1e-15 absolute (same_to_rounding below).  Examples that read data/probes/ are
# skipped when the probes are absent (`make probes`), and those that run a
# shader when there is no Vulkan device.  Output that cannot be
# reproduced (timings) belongs in a ```text block, which is not run.
. "$(dirname "$0")/lib.inc"
ROOT=$(pwd)
# the pages in reading order (an example may use a file an earlier one made);
# docs/choosing.md has its own test (test_choosing_examples.sh)
LABEL=${LABEL:-"README/manual"}
README=${README:-"$ROOT/README.md $ROOT/docs/tour.md $ROOT/docs/rotation.md $ROOT/docs/check-your-kernel.md $ROOT/docs/high-bands.md
$ROOT/docs/scaling.md $ROOT/docs/sweeps.md $ROOT/docs/bad-input.md $ROOT/docs/scenes.md $ROOT/docs/developing.md
$ROOT/docs/CONVENTIONS.md $ROOT/docs/library.md"}
case $SHLAB in /*) bin=$SHLAB ;; *) bin=$ROOT/$SHLAB ;; esac
mkdir -p "$TMP/bin" "$TMP/work" "$TMP/ex"
ln -s "$bin" "$TMP/bin/shlab"
ln -s "$ROOT/data" "$TMP/work/data"
# the example plug-in's source and the ABI header (docs/check-your-kernel.md builds it)
ln -s "$ROOT/src" "$TMP/work/src"
ln -s "$ROOT/tests" "$TMP/work/tests"
# docs/library.md shows its example program with cat and links it to libshlab.so
ln -s "$ROOT/docs" "$TMP/work/docs"
lib=$(dirname "$bin")/libshlab.so
[ -f "$lib" ] && ln -s "$lib" "$TMP/work/libshlab.so" && ln -s "$lib" "$TMP/work/libshlab.so.0"

# split the console blocks into ex/N.cmd (the command) and ex/N.out (its output)
awk -v dir="$TMP/ex" '
    /^```console[ \t]*$/ { on = 1; next }
    on && /^```[ \t]*$/ { on = 0; next }
    on && /^\$ / { n++; f = sprintf("%s/%03d", dir, n); print substr($0, 3) > (f ".cmd"); printf "" > (f ".out"); next }
    on && n { print > (f ".out") }
' $README

# Same text, and every number equal to 1e-13 relative or 1e-15 absolute.
# With ERROR_LOOSE=1 (docs/choosing.md), a number on a line whose key names
# an error ("choice.error_max: ...") may differ by 1e-4 relative, or both be
# below 1e-5: the measured error of a float kernel is rounding, which
# depends on the build (-O1 under the sanitizers) and on the kernel the CPU
# runs; the choices and the model's costs are still compared exactly.
same_to_rounding() {
    awk -v other="$2" -v loose="${ERROR_LOOSE:-0}" '
        function isnum(t) { return t ~ /^-?[0-9]+(\.[0-9]*)?([eE][-+]?[0-9]+)?$/ }
        function abs(x) { return x < 0 ? -x : x }
        { if ((getline o < other) <= 0) { bad = 1; exit }
          n = split($0, a, /[][ ,:\t{}"]+/); m = split(o, b, /[][ ,:\t{}"]+/)
          if (n != m) { bad = 1; exit }
          err = loose == 1 && a[1] ~ /error/
          for (i = 1; i <= n; i++) {
              if (a[i] == b[i]) continue
              if (!isnum(a[i]) || !isnum(b[i])) { bad = 1; exit }
              d = abs(a[i] - b[i]); s = abs(a[i])
              if (d <= 1e-15 || d <= 1e-13 * s) continue
              if (err && (d <= 1e-4 * s || (s < 1e-5 && abs(b[i]) < 1e-5))) continue
              bad = 1; exit
          } }
        END { if (!bad && (getline o < other) > 0) bad = 1; exit bad }' "$1"
}

# examples that run a shader need a Vulkan device (lavapipe: make deps)
have_vk=0
"$bin" verify --quiet --fixture "$ROOT/data/fixtures/rotation/orders_1_10.json" --shader "$ROOT/tests/shaders/rotate_ivanic.glsl" \
    --abi matrix --orders 1 >/dev/null 2>&1 && have_vk=1
count=0
for c in "$TMP"/ex/*.cmd; do
    [ -f "$c" ] || continue
    count=$((count + 1))
    e=${c%.cmd}.out
    cmd=$(cat "$c")
    case $cmd in
    *--shader*)
        if [ "$have_vk" = 0 ]; then ok "# skip README example (no Vulkan device or shlab built without Vulkan): $cmd"; continue; fi ;;
    *libshlab.so*|*./rotate_one*)
        # a program linked to libshlab.so: not under the sanitizers (the
        # instrumented library needs the ASan runtime loaded first)
        if [ "${SANITIZE:-0}" = 1 ] || [ ! -f "$lib" ]; then ok "# skip README example (sanitizer build or no libshlab.so): $cmd"; continue; fi ;;
    *data/probes/*)
        p=$(printf '%s' "$cmd" | grep -o 'data/probes/[^ ]*' | head -1)
        if [ ! -f "$ROOT/$p" ]; then ok "# skip README example (no $p): $cmd"; continue; fi ;;
    esac
    (cd "$TMP/work" && PATH="$TMP/bin:$PATH" sh -c "$cmd") >"$TMP/got" 2>&1
    if cmp -s "$e" "$TMP/got"; then
        ok "$LABEL example: $cmd"
    elif same_to_rounding "$e" "$TMP/got"; then
        # the README shows this machine kind's output; a CPU whose rotation
        # kernel (auto: widest instruction set) rounds differently may differ
        # in the last digits of results that are rounding-level anyway
        ok "$LABEL example (numbers equal to rounding on this build and CPU): $cmd"
    else
        notok "$LABEL example differs: $cmd
$(diff "$e" "$TMP/got" | head -20)"
    fi
done
[ "$count" -ge "${MIN_EXAMPLES:-11}" ] && ok "$LABEL has $count console examples" || notok "only $count console examples found in $README"
