set terminal pngcairo size 900,520 enhanced font ",11"
set output outdir.'/green_vector.png'
f = outdir.'/green_vector.dat'
set xlabel "coefficient index i = l(l+1)+m"
set ylabel "coefficient value"
set xrange [-0.5:15.5]
set xtics 1
set grid ytics
set key top right
set title "Green (2003) Figure 7 light, 4 bands: printed vs exact vs Monte Carlo (10,000 samples)"
plot f using 1:6:(2*$7) with yerrorbars pt 0 lw 1.5 lc rgb "#999999" title "MC mean ± 2σ", \
     f using 1:5 with points pt 6 ps 1.6 lc rgb "#1f77b4" title "exact", \
     f using 1:4 with points pt 2 ps 1.4 lc rgb "#d62728" title "printed"
