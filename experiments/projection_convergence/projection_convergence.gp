set terminal pngcairo size 1100,480 enhanced font ",11"
set output outdir.'/projection_convergence.png'
f = outdir.'/projection_convergence.dat'
set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
set xlabel "function evaluations N"
set ylabel "RMS coefficient error"
set grid lc rgb "#dddddd"
set key bottom left
set xrange [30:4e6]
cols = "#4E79A7 #F28E2B #59A14F #E15759"
set multiplot layout 1,2 title "Projection of order 4: RMS error of the 16 coefficients against evaluations (random: mean of 32 seeds)"
do for [s=0:1] {
  set title (s==0 ? "Green's Figure 7 light (kinks)" : "smooth lobe max(0,cos θ)^7")
  set yrange [(s == 0 ? 1e-7 : 1e-17):(s == 0 ? 1 : 10)]
  # guide lines through the first random and the first stratified point
  a = 1.2e-1 * sqrt(64.0); b = (s == 0 ? 8e-2 : 5e-2) * 64
  plot for [r=0:3] f index (4*s+r) using 3:($4>0?$4:1e-17) with linespoints pt 7 ps 0.6 lw 1.5 \
         lc rgb word(cols, r+1) title word("random stratified QMC quad", r+1), \
       a*x**(-0.5) dt 2 lw 1.5 lc rgb "#444444" title "∝ N^{-1/2}", \
       b*x**(-1) dt 4 lw 1.5 lc rgb "#444444" title "∝ N^{-1}"
}
unset multiplot
