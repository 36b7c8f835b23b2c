load 'experiments/common/style.gp'
set terminal pngcairo size 1000,540 enhanced font ",11"
set output outdir.'/orthonormality.png'
f = outdir.'/orthonormality.dat'
eval logy(1e-16, 10)
set xlabel "order n (bands 0..n−1)"
set ylabel "max |G_{ij} − δ_{ij}| (absolute)"
eval key_right
set xrange [0:65]
set xtics 8
set title "Orthonormality of each projection rule (about 4096 nodes; Gram matrix G of the n² basis functions)"
# 45 Gauss-Legendre nodes integrate polynomials of degree ≤ 89 in cos θ exactly:
# products of two functions of degree ≤ 44, i.e. orders n ≤ 45
set arrow 1 from 45.5, graph 0 to 45.5, graph 1 nohead dt 3 lc rgb "#666666"
set label 1 "product rule exact\nfor n ≤ 45" at 44.5, 1e-11 right font ",9" tc rgb "#333333" front boxed
plot for [c=2:5] f using 1:(column(c)>0?column(c):1e-17) with linespoints lt (c-1) ps 0.5 lw 1.5 \
     title word("product(45×90) stratified random Sobol", c-1)
