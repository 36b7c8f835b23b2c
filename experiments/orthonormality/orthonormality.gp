set terminal pngcairo size 900,520 enhanced font ",11"
set output outdir.'/orthonormality.png'
f = outdir.'/orthonormality.dat'
set logscale y
set format y "10^{%T}"
set xlabel "order n"
set ylabel "max |G_{ij} − δ_{ij}|"
set grid
set key bottom right
set title "Orthonormality of each projection rule (about 4096 nodes)"
plot for [c=2:5] f using 1:(column(c)>0?column(c):1e-17) with linespoints pt 7 ps 0.5 lw 1.5 title word("product(45×90) stratified random Sobol", c-1)
