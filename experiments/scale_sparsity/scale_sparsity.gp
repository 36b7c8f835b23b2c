# non-zero entries of the scaling matrix relative to the pattern bound N(2N²+1)/3
load 'experiments/common/style.gp'
set terminal pngcairo size 1150,720 enhanced font ",11"
set output outdir.'/scale_sparsity.png'
f = outdir.'/sparsity.dat'
set xlabel "order N (bands 0..N−1)"
set ylabel "non-zero entries / N(2N²+1)/3 (fraction of the bound)"
set title "Non-zero entries of the SH scaling matrix relative to the pattern bound\n{/*0.8 cases with the same counts coincide: their markers are drawn nested (largest first)}"
lab(c) = system(sprintf("sed -n '%dp' %s/sparsity_cases.txt", c + 5, outdir))
# one style per case from style.gp's cycle (11 cases: colours, points and, from the 8th, dashes)
set key at screen 0.5, screen 0.01 center bottom maxrows 4 width 2 samplen 2.5 font ",10"
set bmargin 9
set xrange [0.5:16.5]
set yrange [0.45:1.04]
set xtics 1,1,16
plot for [c=0:10] f using 1:(column(3+2*c)/$2) with linespoints lt (c+1) lw 1.3 pt (c % 2 ? 6 + 2*(c/2) % 10 : 4 + 2*(c/2) % 10) \
     ps (2.4 - 0.17*c) title lab(c) noenhanced
