#!/bin/sh
# refresh_examples.sh FILE... — rewrite the output of every console example
# in FILE (a ```console block: "$ COMMAND" lines, each followed by its
# output) by running the command, as tests/cli/test_readme_examples.sh runs
# it: in a scratch directory with the repository's data/ visible and `shlab`
# meaning $SHLAB (default build/shlab).  The command is the source; its
# output in the document is what it printed.  `make examples` runs this on
# docs/choosing.md, and `make report` after the cost model changes.
set -eu
ROOT=$(pwd)
SHLAB=${SHLAB:-build/shlab}
case $SHLAB in /*) bin=$SHLAB ;; *) bin=$ROOT/$SHLAB ;; esac
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT INT TERM
mkdir -p "$T/bin" "$T/work"
ln -s "$bin" "$T/bin/shlab"
ln -s "$ROOT/data" "$T/work/data"
for f in "$@"; do
    out=$T/new.md
    : >"$out"
    on=0
    skip=0
    while IFS= read -r line || [ -n "$line" ]; do
        case $on:$line in
        0:'```console')
            on=1; printf '%s\n' "$line" >>"$out" ;;
        1:'```')
            on=0; skip=0; printf '%s\n' "$line" >>"$out" ;;
        1:'$ '*)
            skip=1
            printf '%s\n' "$line" >>"$out"
            cmd=${line#\$ }
            (cd "$T/work" && PATH="$T/bin:$PATH" sh -c "$cmd") >>"$out" 2>&1 || true ;;
        1:*)
            [ "$skip" = 1 ] || printf '%s\n' "$line" >>"$out" ;;
        *)
            printf '%s\n' "$line" >>"$out" ;;
        esac
    done <"$f"
    if cmp -s "$out" "$f"; then echo "refresh_examples: $f unchanged"; else cp "$out" "$f"; echo "refresh_examples: $f rewritten"; fi
done
