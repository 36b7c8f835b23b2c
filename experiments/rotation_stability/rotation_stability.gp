set terminal pngcairo size 900,560 enhanced font ",11"
set logscale y
set format y "10^{%L}"
set xlabel "band l"
set ylabel "max |R R^T - I| over the rotation set"
set grid
set key top left
set yrange [1e-17:1e2]
set output outdir.'/stability_double.png'
set title "Exact rotation methods, double (sweeps stop once orth > 1)"
set logscale x
set xrange [1:1000]
plot for [m in "zxzxz blanco ivanic choi wigner"] outdir.'/'.m.'_double.dat' using ($1+0):($2>0?$2:1e-17) with linespoints pt 7 ps 0.5 title m
set output outdir.'/stability_float.png'
set title "Exact rotation methods, float arithmetic"
unset logscale x
set xrange [0:64]
set yrange [1e-9:1e1]
plot for [m in "zxzxz blanco ivanic choi wigner"] outdir.'/'.m.'_float.dat' using 1:($2>0?$2:1e-9) with linespoints pt 7 ps 0.5 title m
