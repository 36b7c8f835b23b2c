set terminal pngcairo size 1100,720 enhanced font ",11"
set output outdir.'/scale_sparsity.png'
f = outdir.'/sparsity.dat'
set xlabel "order N"
set ylabel "non-zeros / N(2N²+1)/3"
set grid lc rgb "#dddddd"
set title "Non-zero entries of the SH scaling matrix relative to the pattern bound\n{/*0.8 cases with the same counts coincide: their markers are drawn nested (largest first)}"
lab(c) = system(sprintf("sed -n '%dp' %s/sparsity_cases.txt", c + 5, outdir))
cols = "#4E79A7 #F28E2B #E15759 #76B7B2 #59A14F #EDC948 #B07AA1 #FF9DA7 #9C755F #000000 #17BECF"
pts  = "6 4 8 12 10 14 6 4 8 12 10"
sdt(c) = c < 7 ? 1 : 2
set key at screen 0.5, screen 0.01 center bottom maxrows 3 width 2 samplen 2 font ",10"
set bmargin 8
set xrange [0.5:16.5]
set yrange [0.45:1.04]
set xtics 1,1,16
plot for [c=0:10] f using 1:(column(3+2*c)/$2) with linespoints lw 1.2 dt sdt(c) \
     pt int(word(pts, c+1)) ps (2.4 - 0.17*c) lc rgb word(cols, c+1) title lab(c) noenhanced
