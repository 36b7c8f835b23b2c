# sht_accuracy.gp — the transforms' error against lmax, shlab and libsharp
load 'experiments/common/style.gp'
set terminal pngcairo size 1300,640 enhanced font ",11"
set output outdir.'/sht_accuracy.png'
f = outdir.'/sht_accuracy.dat'
fp = outdir.'/peers/sht_accuracy_peers.dat'
have_peers = system('test -f '.fp.' && echo 1 || echo 0') + 0
set logscale xy
set xrange [24:5200]
set xtics (32, 64, 128, 256, 512, 1024, 2047, 4096)
eval logy(1e-16, 1e-10)
set xlabel "lmax L (Gauss grid of L+1 rings × 2L+2 points)"
set key outside below center horizontal maxcols 2 Left reverse samplen 3 spacing 1.1 width -2
shlab = ccol(1); sharp = ccol(2); grey = "#555555"
set multiplot layout 1,2 title "Fast transforms against an independent truth (seeded N(0,1) coefficients for every (l,m) ≤ L, one thread)"
set title "synthesis: max|f − f_{true}| / max|f_{true}| on the test rings"
set ylabel "error relative to max|f| (dimensionless)"
set lmargin 10; set rmargin 3
# the polar path (src/project/sht_polar.c) runs from lmax SHT_POLAR_LMIN = 512
set arrow 1 from 512,3e-15 to 512,1.2e-14 lc rgb grey lw 1
set label 1 "polar path\nfrom lmax 512" at 512,2e-15 center font ",10" tc rgb grey
eval budgetl(91, 1e-12, "bound of the tests")
plot \
     f using 1:4 with linespoints pt 7 ps 0.7 lw 2 lc rgb shlab title "shlab", \
     (have_peers ? fp : f) using 1:(have_peers ? $4 : 1/0) with linespoints pt 5 ps 0.7 lw 2 lc rgb sharp title "libsharp", \
     (have_peers ? fp : f) using 1:(have_peers ? $6 : 1/0) with linespoints pt 2 ps 0.8 lw 1.2 dt 3 lc rgb grey title "shlab vs libsharp, every point"
unset arrow 1; unset label 1
set title "round trip (synthesis, then analysis)"
set ylabel "coefficient error (relative)"
plot \
     f using 1:2 with linespoints pt 7 ps 0.7 lw 2 lc rgb shlab title "shlab ‖Δc‖_2/‖c‖_2", \
     f using 1:3 with linespoints pt 6 ps 0.7 lw 1.2 dt 2 lc rgb shlab title "shlab max|Δc|/max|c|", \
     (have_peers ? fp : f) using 1:(have_peers ? $2 : 1/0) with linespoints pt 5 ps 0.7 lw 2 lc rgb sharp title "libsharp ‖Δc‖_2/‖c‖_2", \
     (have_peers ? fp : f) using 1:(have_peers ? $3 : 1/0) with linespoints pt 4 ps 0.7 lw 1.2 dt 2 lc rgb sharp title "libsharp max|Δc|/max|c|"
unset multiplot
