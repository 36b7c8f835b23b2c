#!/bin/sh
# test_fuzz_corpus.sh — replay every fuzz harness over its seed corpus
# (tests/fuzz/corpus/<h>/) with the corpus-replay main: under
# make check SANITIZE=1 this runs every seed through ASan/UBSan.
. "$(dirname "$0")/lib.inc"
BUILD=${BUILD:-build}
for h in exr fixture candidate coeffs light rotation mesh merge; do
    bin="$BUILD/fuzz/replay_$h"
    if [ ! -x "$bin" ]; then notok "replay $h: $bin not built"; continue; fi
    cnt=$(find "tests/fuzz/corpus/$h" -type f | wc -l)
    if "$bin" "tests/fuzz/corpus/$h" >"$TMP/out" 2>"$TMP/err" && grep -q "^replay: $cnt inputs" "$TMP/out"; then
        ok "fuzz corpus $h: $cnt inputs replayed"
    else
        notok "fuzz corpus $h: $(grep -E 'ERROR|SUMMARY|contract' "$TMP/err" | head -3)"
    fi
done
