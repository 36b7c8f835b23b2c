# The long part (reports/rotation_stability/long): the stable methods to
# l = 4000.  orth is exact up to l = 500 (solid lines, filled markers); above,
# the two-probe estimate (dashed, open markers), which runs about 10x below the
# exact value at the same band: the dotted line marks the change of measure.
load 'experiments/common/style.gp'
set terminal pngcairo size 1100,580 enhanced font ",11"
set xlabel "band l"
set ylabel "max |R R^T − I| over the rotation set (absolute)"
eval key_right
eval logx(1, 4500)
set xtics ("1" 1, "10" 10, "100" 100, "500" 500, "1000" 1000, "4000" 4000)
set format x "%g"
eval logy(1e-17, 1e-10)
set output outdir.'/stability_long.png'
set title "Stable rotation methods to l = 4000, double (0 drawn at 10^{-17})"
sw = 500
set arrow 1 from sw, graph 0 to sw, graph 1 nohead dt 3 lw 1.5 lc rgb "#444444"
set label 1 "l = 500: exact ← | → two-probe estimate\n(about 10× below exact:\nthe step is not an improvement)" \
    at sw*0.94, 1.5e-16 right font ",9" tc rgb "#333333" front boxed
ms = "halfpi blanco zxzxz"
plot for [m in ms] outdir.'/'.m.'_double.dat' using ($1+0):($5 == 1 ? ($2>0?$2:1e-17) : 1/0) with linespoints \
        lw 1.5 pt mpt(m) ps 0.6 lc rgb mcol(m) title m, \
     for [m in ms] outdir.'/'.m.'_double.dat' using ($1+0):($5 == 0 ? ($2>0?$2:1e-17) : 1/0) with linespoints \
        lw 1.5 dt 2 pt 6 ps 0.7 lc rgb mcol(m) notitle, \
     NaN with linespoints lw 1.5 dt 2 pt 6 ps 0.7 lc rgb "#444444" title sprintf("l > %d: two-probe estimate", sw)
