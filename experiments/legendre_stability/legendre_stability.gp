set terminal pngcairo size 1000,560 enhanced font ",11"
set output outdir.'/legendre_stability.png'
set logscale y
set format y "10^{%T}"
set xlabel "degree l"
set ylabel "relative error of the addition theorem"
set key outside right
set title "Normalised associated Legendre functions: shlab vs GSL"
f = outdir.'/legendre_stability.dat'
plot for [i=0:4] f index i using 1:($3>0?$3:1e-17) with lines lw 1.5 lc i+1 title sprintf("shlab θ=%s°", word("0.5 1 10 45 89", i+1)), \
     for [i=0:4] f index i using 1:($4>0?$4:1e-17) with lines dt 2 lw 1 lc i+1 title sprintf("GSL θ=%s°", word("0.5 1 10 45 89", i+1))
