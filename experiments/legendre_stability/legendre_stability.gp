set terminal pngcairo size 1300,520 enhanced font ",11"
set output outdir.'/legendre_stability.png'
set logscale y
set format y "10^{%T}"
set xlabel "degree l"
set ylabel "relative error of the addition theorem"
set grid lc rgb "#dddddd"
set yrange [1e-17:1e-11]
set xrange [0:2500]
f = outdir.'/legendre_stability.dat'
cols = "#4E79A7 #F28E2B #59A14F #E15759 #B07AA1"
th = "0.5 1 10 45 89"
set multiplot layout 1,2 margins 0.06,0.88,0.12,0.88 spacing 0.06 \
    title "Normalised associated Legendre functions: relative error of Σ_{m=-l..l} P̄_l^{|m|}(cos θ)² = (2l+1)/4π, every 10th l (0 drawn at 10^{-17})"
set title "shlab (normalised recurrence)"
unset key
plot for [i=0:4] f index i using 1:($3>0?$3:1e-17) with lines lw 1.2 lc rgb word(cols, i+1) title sprintf("θ = %s°", word(th, i+1))
set title "GSL (gsl\\_sf\\_legendre\\_array\\_e)"
set key at screen 0.995, screen 0.86 right top Left reverse
plot for [i=0:4] f index i using 1:($4>0?$4:1e-17) with lines lw 1.2 lc rgb word(cols, i+1) title sprintf("θ = %s°", word(th, i+1))
unset multiplot
