# cost_table.awk — data/cost_model.tsv (the cost model's calibration, written
# by the trade_atlas experiment) as C initialisers for src/lab/cost_model.c:
# the "# source: " line becomes SH_COST_SOURCE, every data row one struct.
BEGIN { FS = "\t" }
/^# source: / {
    s = substr($0, 11); gsub(/\\/, "\\\\", s); gsub(/"/, "\\\"", s)
    printf "#define SH_COST_SOURCE \"%s\"\n", s; next
}
/^#/ || $1 == "order" || NF < 11 { next }
{
    printf "{%d, \"%s\", \"%s\", \"%s\", \"%s\", %d, \"%s\", %.17g, %.17g, %.17g, %.17g},\n",
           $1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11
}
