# rotation_stability.gp — orthogonality error against the band, double and float
load 'experiments/common/style.gp'
set terminal pngcairo size 1100,580 enhanced font ",11"
set xlabel "band l"
set ylabel "max |R R^T − I| over the rotation set (absolute)"
eval key_right
ms = "zxzxz blanco halfpi ivanic choi wigner"
set output outdir.'/stability_double.png'
set title "Exact rotation methods, double: a sweep stops once the error exceeds 1; 0 drawn at 10^{-17}"
eval logy(1e-17, 1e2)
eval logx(1, 1000)
set xtics ("1" 1, "10" 10, "100" 100, "1000" 1000)
set format x "%g"
# orth is exact up to l = 128 (solid); above, a two-probe estimate, 5-10x
# below the exact maximum at the same band (dashed, open markers): the step
# is the change of measure, not an improvement.  The note sits in the empty
# band of the plot, clear of the tick labels.
set arrow 1 from 128, graph 0 to 128, graph 1 nohead dt 3 lc rgb "#666666"
set label 1 "l ≤ 128: exact;\nabove: two-probe\nestimate, 5–10×\nbelow exact (the\nstep is no\nimprovement)" \
    at 240, 1e-6 left font ",9" tc rgb "#333333" front boxed
plot for [m in ms] outdir.'/'.m.'_double.dat' using ($1+0):($5 == 1 ? ($2>0?$2:1e-17) : 1/0) with linespoints \
        lw 1.5 pt mpt(m) ps 0.5 lc rgb mcol(m) title m, \
     for [m in ms] outdir.'/'.m.'_double.dat' using ($1+0):($5 == 0 || $1 == 128 ? ($2>0?$2:1e-17) : 1/0) with linespoints \
        lw 1.5 dt 2 pt 6 ps 0.6 lc rgb mcol(m) notitle, \
     NaN with linespoints lw 1.5 dt 2 pt 6 ps 0.6 lc rgb "#444444" title "l > 128: two-probe estimate"
unset arrow 1
unset label 1
set output outdir.'/stability_float.png'
set title "Exact rotation methods, float arithmetic (exact orthogonality error; 0 drawn at 10^{-9})"
unset logscale x
set xrange [0:64]
set xtics 8
set mxtics 2
eval logy(1e-9, 1e1)
plot for [m in ms] outdir.'/'.m.'_float.dat' using 1:($2>0?$2:1e-9) with linespoints lw 1.5 pt mpt(m) ps 0.5 lc rgb mcol(m) title m
