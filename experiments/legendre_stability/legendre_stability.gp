load 'experiments/common/style.gp'
set terminal pngcairo size 1350,540 enhanced font ",11"
set output outdir.'/legendre_stability.png'
eval logy(1e-17, 1e-11)
set xlabel "degree l"
set ylabel "relative error of the addition theorem"
set xrange [0:2500]
set xtics 500
f = outdir.'/legendre_stability.dat'
th = "0.5 1 10 45 89"
set multiplot layout 1,2 margins 0.06,0.88,0.13,0.86 spacing 0.06 \
    title "Normalised associated Legendre functions: relative error of Σ_{m=-l..l} P̄_l^{|m|}(cos θ)² = (2l+1)/4π, every 10th l (0 drawn at 10^{-17})"
set title "shlab (normalised recurrence)"
unset key
plot for [i=0:4] f index i using 1:($3>0?$3:1e-17) with lines lt (i+1) lw 1.2 title sprintf("θ = %s°", word(th, i+1))
set title "GSL (gsl\\_sf\\_legendre\\_array\\_e)"
set key at screen 0.995, screen 0.86 right top Left reverse title "polar angle"
plot for [i=0:4] f index i using 1:($4>0?$4:1e-17) with lines lt (i+1) lw 1.2 title sprintf("θ = %s°", word(th, i+1))
unset multiplot
