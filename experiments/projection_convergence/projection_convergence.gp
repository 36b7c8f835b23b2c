set terminal pngcairo size 1100,480 enhanced font ",11"
set output outdir.'/projection_convergence.png'
f = outdir.'/projection_convergence.dat'
set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
set xlabel "function evaluations N"
set ylabel "RMS coefficient error"
set grid
set key bottom left
set multiplot layout 1,2
do for [s=0:1] {
  set title (s==0 ? "Green's Figure 7 light (kinks)" : "smooth lobe max(0,cos θ)^7")
  plot for [r=0:3] f index (4*s+r) using 3:($4>0?$4:1e-17) with linespoints pt 7 ps 0.6 lw 1.5 title word("random stratified QMC quad", r+1), \
       1e-1*x**(-0.5) dt 2 lc rgb "gray" title "N^{-1/2}", 3*x**(-1) dt 3 lc rgb "gray" title "N^{-1}"
}
unset multiplot
