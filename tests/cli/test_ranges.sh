#!/bin/sh
# test_ranges.sh — docs/ranges.md cannot drift from the code: every row of
# its table "The limits in the code" names a file and the exact code that sets
# the limit, and that code must be in that file (a limit changed in the code
# fails here until the page, and the test at the new upper end, follow).
# Then the program itself at a few limits: the largest value accepted runs,
# the next one is refused in one line (truth: the limits the page states).
. tests/cli/lib.inc
DOC=docs/ranges.md

[ -f "$DOC" ] && ok "docs/ranges.md exists" || notok "docs/ranges.md is missing"

# ---- the table: | limit | value | `file` | `code` |  ("\|" is a literal |)
awk '/^## The limits in the code/ { on = 1; next } /^## / { on = 0 } on && /^\| .* \| `[^`]*` \| `/' "$DOC" |
    sed 's/\\|/\x01/g' >"$TMP/rows"
nrows=$(wc -l <"$TMP/rows")
[ "$nrows" -ge 30 ] && ok "the limits table has $nrows rows" || notok "the limits table has $nrows rows (expected >= 30)"
bad=0
while IFS= read -r row; do
    file=$(printf '%s\n' "$row" | awk -F'|' '{ print $4 }' | sed 's/^ *`//; s/` *$//')
    code=$(printf '%s\n' "$row" | awk -F'|' '{ print $5 }' | sed 's/^ *`//; s/` *$//' | tr '\001' '|')
    if [ ! -f "$file" ]; then
        notok "limit row names a missing file: $file"; bad=1
    elif ! grep -qF -- "$code" "$file"; then
        notok "$file no longer contains: $code (docs/ranges.md is stale)"; bad=1
    fi
done <"$TMP/rows"
[ "$bad" = 0 ] && ok "every limit in docs/ranges.md is the code's"

# every public header constant named *MAX* is in the page (a new limit must be audited)
for c in $(grep -ho '#define SH[A-Z_]*MAX[A-Z_]* ' src/shlab/*.h | awk '{ print $2 }' | sort -u); do
    case "$c" in SH_SHARD_MAX | SH_MESH_MAX_ELEMS | SH_MESH_MAX_BYTES | SH_TRANSFER_MAX_BOUNCES | SH_IMAGE_MAX_CHANNELS | \
        SH_LIGHT_MAX_VALUE | SH_ROT_DEFAULT_ZXZXZ_MAX) continue ;; # resource guards and parameters (page, "Not covered")
    esac
    grep -qF "#define $c " "$DOC" || { notok "public limit $c is not in docs/ranges.md"; bad=1; }
done
[ "$bad" = 0 ] && ok "every public *MAX* limit is audited in docs/ranges.md"

# ---- the program at the limits
expect_usage_error "eval --order 4098 (SHLAB_MAX_ORDER + 1)" eval --order 4098 --dir 0,0,1
grep -q "4097" "$TMP/err" && ok "the refusal names 4097" || notok "refusal: $(cat "$TMP/err")"
expect_success "rotmat --band 200 --method ivanic (its largest band)" rotmat --band 200 --method ivanic --euler 0.4,1.2,-1.3 --format csv
expect_usage_error "rotmat --band 201 --method ivanic" rotmat --band 201 --method ivanic --euler 0.4,1.2,-1.3
expect_usage_error "rotmat --band 201 --method choi" rotmat --band 201 --method choi --euler 0.4,1.2,-1.3
expect_success "rotmat --band 60 --method wigner" rotmat --band 60 --method wigner --euler 0.4,1.2,-1.3 --format csv
expect_usage_error "rotmat --band 61 --method wigner" rotmat --band 61 --method wigner --euler 0.4,1.2,-1.3
expect_success "rotmat --band 127 --method taylor1.5" rotmat --band 127 --method taylor1.5 --euler 0.4,0.01,-1.3 --format csv
expect_usage_error "rotmat --band 128 --method taylor1.5" rotmat --band 128 --method taylor1.5 --euler 0.4,0.01,-1.3
expect_usage_error "stability --method zxzxz --bands 1401" stability --method zxzxz --bands 1401 --quiet
expect_usage_error "reconstruct --width 11586 (more than 2^26 pixels)" reconstruct --order 1 --coeffs 1 --width 11586 --out "$TMP/x.exr"
[ ! -e "$TMP/x.exr" ] && ok "no file left by the refused reconstruction" || notok "reconstruct left $TMP/x.exr"
