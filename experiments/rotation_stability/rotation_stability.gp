load 'experiments/common/style.gp'
set terminal pngcairo size 1000,560 enhanced font ",11"
set logscale y
set format y "10^{%T}"
set xlabel "band l"
set ylabel "max |R R^T − I| over the rotation set"
set key top left Left reverse
set yrange [1e-17:1e2]
set output outdir.'/stability_double.png'
set title "Exact rotation methods, double (a sweep stops once the error exceeds 1; 0 drawn at 10^{-17})"
set logscale x
set xrange [1:1000]
# orth is exact up to l = 128 (solid); above, a two-probe estimate, 5-10x
# below the exact maximum at the same band (dashed, open markers): the step
# is the change of measure, not an improvement
set arrow 1 from 128, graph 0 to 128, graph 1 nohead dt 3 lc rgb "#666666"
set label 1 "exact ← | → two-probe estimate\n(5–10× below exact:\nthe step is not an improvement)" at 134, 3e-16 font ",9" tc rgb "#444444"
ms = "zxzxz blanco halfpi ivanic choi wigner"
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
set yrange [1e-9:1e1]
plot for [m in ms] outdir.'/'.m.'_float.dat' using 1:($2>0?$2:1e-9) with linespoints lw 1.5 pt mpt(m) ps 0.5 lc rgb mcol(m) title m
