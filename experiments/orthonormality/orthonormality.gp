set terminal pngcairo size 900,520 enhanced font ",11"
set output outdir.'/orthonormality.png'
f = outdir.'/orthonormality.dat'
set logscale y
set format y "10^{%T}"
set xlabel "order n"
set ylabel "max |G_{ij} − δ_{ij}|"
set grid lc rgb "#dddddd"
set key bottom right
set xrange [0:65]
set yrange [1e-16:10]
set title "Orthonormality of each projection rule (about 4096 nodes; Gram matrix G of the n² basis functions)"
# 45 Gauss-Legendre nodes integrate polynomials of degree ≤ 89 in cos θ exactly:
# products of two functions of degree ≤ 44, i.e. orders n ≤ 45
set arrow 1 from 45.5, graph 0 to 45.5, graph 1 nohead dt 3 lc rgb "#666666"
set label 1 "product rule exact\nfor n ≤ 45" at 44.5, 1e-11 right font ",9" tc rgb "#444444"
cols = "#4E79A7 #59A14F #E15759 #F28E2B"
plot for [c=2:5] f using 1:(column(c)>0?column(c):1e-17) with linespoints pt 7 ps 0.5 lw 1.5 lc rgb word(cols, c-1) \
     title word("product(45×90) stratified random Sobol", c-1)
