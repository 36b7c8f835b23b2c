# style.gp — one look for every plot, loaded first by every experiments/*/*.gp
# (`load 'experiments/common/style.gp'`, then the script's own settings).
#
# Colours: the Okabe & Ito (2008) palette without its yellow (too light on
# white), then Paul Tol's "muted" wine, olive, indigo and teal: distinct for
# the common colour-vision deficiencies.  Series differ in point type and,
# from the eighth on, in dash type too, so that they stay apart in grey print.
# Linetypes 1..12 are this cycle: `lt i`, or plain `plot for [i=...]`, use it.
set terminal pngcairo size 1200,520 enhanced font ",11"
set encoding utf8
set grid lc rgb "#e4e4e4" lw 1
set border lc rgb "#444444"
set key noopaque samplen 3 spacing 1.15
set style textbox opaque noborder margins 1,1
ccols = "#0072B2 #E69F00 #009E73 #D55E00 #CC79A7 #56B4E9 #000000 #882255 #999933 #332288 #44AA99 #777777"
cpts  = "7 5 9 11 13 4 6 8 10 12 14 2"
cdts  = "1 1 1 1 1 1 1 2 2 2 4 4"
NCYC = words(ccols)
ccol(i) = word(ccols, (int(i) - 1) % NCYC + 1)
cpt(i) = int(word(cpts, (int(i) - 1) % NCYC + 1))
cdt(i) = int(word(cdts, (int(i) - 1) % NCYC + 1))
do for [i = 1:NCYC] {
    set linetype i lc rgb ccol(i) pt cpt(i) dt cdt(i) lw 1.6 ps 0.8
}
set linetype cycle NCYC

# Every rotation method keeps its colour, point type and dash type in every
# figure: exact methods solid, the Taylor approximations dashed (each its own
# dash type).
mname = "z ivanic zxzxz choi blanco wigner reference taylor1 taylor1.5 taylor2 zxzxz_dense matrix_to_angles halfpi direct zh"
mcols = "#56B4E9 #E69F00 #0072B2 #009E73 #CC79A7 #882255 #777777 #D55E00 #000000 #999933 #0072B2 #777777 #332288 #44AA99 #AA4499"
mpts  = "4 5 7 9 11 13 1 6 8 10 3 2 15 12 14"
mdts  = "1 1 1 1 1 1 1 2 5 4 3 4 1 1 1"
midx(m) = sum [k = 1:words(mname)] (word(mname, k) eq m ? k : 0)
mcol(m) = word(mcols, midx(m) > 0 ? midx(m) : 7)
mpt(m) = int(word(mpts, midx(m) > 0 ? midx(m) : 7))
mdt(m) = int(word(mdts, midx(m) > 0 ? midx(m) : 7))
mlab(m) = m eq "zxzxz_dense" ? "zxzxz, dense X (test)" : m eq "matrix_to_angles" ? "matrix → angles alone" : m

# Log axes with readable ticks: eval logy(lo, hi) (and logx) sets the range,
# the format 10^{k} and a major tick every decade (every 2nd or 3rd decade
# when the range spans more than 8 or 14 decades).
# (On a log axis `set ytics START, FACTOR` puts ticks at START·FACTOR^k, so
# START must be a power of ten for the labels 10^{%T} to be right.)
logstep(lo, hi) = log10(hi / lo) > 14 ? 1000 : log10(hi / lo) > 8 ? 100 : 10
logstart(lo) = 10.0 ** ceil(log10(lo) - 1e-9)
logy(lo, hi) = sprintf("set logscale y; set yrange [%g:%g]; set format y '10^{%%T}'; set ytics %.17g, %g; " . \
                       "set mytics 10", lo, hi, logstart(lo), logstep(lo, hi))
logx(lo, hi) = sprintf("set logscale x; set xrange [%g:%g]; set format x '10^{%%T}'; set xtics %.17g, %g; " . \
                       "set mxtics 10", lo, hi, logstart(lo), logstep(lo, hi))

# Budget or goal lines, labelled: eval budget(N, y, "text") draws object N
# (an arrow across the panel at y, first axis) and label N (at the right end,
# above the line, on an opaque box); budgetl(...) puts the label at the left
# end.  Numbers from
# 90 up are free for them.
budget(n, y, t) = sprintf("set arrow %d from graph 0, first %.17g to graph 1, first %.17g nohead dt 3 lw 1.4 " . \
                          "lc rgb '#555555' back; set label %d \"%s\" at graph 0.985, first %.17g right " . \
                          "offset 0,0.55 font ',9' tc rgb '#333333' front boxed", n, y, y, n, t, y)
budgetl(n, y, t) = sprintf("set arrow %d from graph 0, first %.17g to graph 1, first %.17g nohead dt 3 lw 1.4 " . \
                           "lc rgb '#555555' back; set label %d \"%s\" at graph 0.015, first %.17g left " . \
                           "offset 0,0.55 font ',9' tc rgb '#333333' front boxed", n, y, y, n, t, y)
# budgeto(...): the label outside the panel, just right of its border (for a
# panel with room there: it then covers no data).
budgeto(n, y, t) = sprintf("set arrow %d from graph 0, first %.17g to graph 1, first %.17g nohead dt 3 lw 1.4 " . \
                           "lc rgb '#555555' back; set label %d \"%s\" at graph 1.01, first %.17g left " . \
                           "font ',9' tc rgb '#333333' front", n, y, y, n, t, y)
nobudget(n) = sprintf("unset arrow %d; unset label %d", n, n)

# The NOISY stamp: only on a panel whose runs broke the noise criterion; the
# script reads that from the panel's own noise data and passes the text
# (empty: no stamp).  eval stamp("...") / eval nostamp
stamp(t) = strlen(t) > 0 ? sprintf("set label 99 \"%s\" at graph 0.02, graph 0.93 left tc rgb '#B00000' " . \
                                   "font ',10' front boxed", t) : "unset label 99"
nostamp = "unset label 99"

# Legends outside the data: to the right of the panel (key_right) or in a
# band below it (key_below); in a multiplot, a script gives the last panel
# `set key at screen X, Y` instead.
key_right = "set key outside right top Left reverse samplen 2.5 spacing 1.1 font ',10' title ''"
key_below = "set key outside below center horizontal Left reverse samplen 2.5 spacing 1.1 font ',10' title ''"
