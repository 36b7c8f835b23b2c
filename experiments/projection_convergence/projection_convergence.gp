load 'experiments/common/style.gp'
set terminal pngcairo size 1250,500 enhanced font ",11"
set output outdir.'/projection_convergence.png'
f = outdir.'/projection_convergence.dat'
eval logx(30, 4e6)
set xlabel "function evaluations N"
set ylabel "RMS coefficient error (absolute)"
set multiplot layout 1,2 margins 0.07,0.82,0.13,0.85 spacing 0.07 \
    title "Projection of order 4: RMS error of the 16 coefficients against evaluations (random: mean of 32 seeds)"
unset key
do for [s=0:1] {
  set title (s==0 ? "Green's Figure 7 light (kinks)" : "smooth lobe max(0,cos θ)^7")
  if (s == 0) { eval logy(1e-7, 1) } else { eval logy(1e-17, 10) }
  if (s == 1) { set key at screen 0.83, screen 0.85 left top Left reverse samplen 3 spacing 1.2 }
  # guide lines through the first random and the first stratified point
  a = 1.2e-1 * sqrt(64.0); b = (s == 0 ? 8e-2 : 5e-2) * 64
  plot for [r=0:3] f index (4*s+r) using 3:($4>0?$4:1e-17) with linespoints lt (r+1) ps 0.6 lw 1.5 \
         title word("random stratified QMC product-rule", r+1), \
       a*x**(-0.5) dt 2 lw 1.5 lc rgb "#444444" title "∝ N^{-1/2}", \
       b*x**(-1) dt 4 lw 1.5 lc rgb "#444444" title "∝ N^{-1}"
}
unset multiplot
