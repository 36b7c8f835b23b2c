# Figure 3 (Křivánek et al. 2005) reproduced: rows max / mean / lobe, columns order 5 / 8.
set terminal pngcairo size 1100,1150 enhanced font ",10"
set output outdir.'/taylor_error_fig3.png'
f = outdir.'/figure3.dat'
set multiplot layout 3,2 title "Error of the Taylor-approximated rotation about y (unit vectors; lobe cos^7)"
set grid
set logscale y
set format y "10^{%L}"
set yrange [1e-6:20]
set xlabel "β (degrees)"
set key top left
names = "max mean lobe"
orders = "5 8"
do for [r=1:3] {
  do for [o=0:1] {
    set ylabel word(names, r).' error'
    set title 'order '.word(orders, o+1)
    plot f index o using 1:(column(1+r)) with lines lw 2 title 'Taylor 1', \
         f index o using 1:(column(4+r)) with lines lw 2 title 'Taylor 1.5', \
         f index o using 1:(column(7+r)) with lines lw 2 title 'Taylor 2'
  }
}
unset multiplot

set terminal pngcairo size 1200,800 enhanced font ",10"
set output outdir.'/taylor_error_ext.png'
g = outdir.'/extended.dat'
set multiplot layout 2,3 title "Orders 2-16, β to 90°: lobe error (top) and max singular value (bottom)"
set yrange [1e-8:100]
set key off
tn = "1 1.5 2"
do for [t=0:2] {
  set title 'Taylor '.word(tn, t+1).': lobe error (orders 2..16, darker = higher)'
  set ylabel 'lobe error'
  plot for [n=0:14] g index n using 2:(column(5+3*t)) with lines lc rgb sprintf("#%02x%02x%02x", 200-12*n, 200-12*n, 255) notitle
}
do for [t=0:2] {
  set title 'Taylor '.word(tn, t+1).': max σ(D)'
  set ylabel 'max error'
  plot for [n=0:14] g index n using 2:(column(3+3*t)) with lines lc rgb sprintf("#%02x%02x%02x", 255, 200-12*n, 200-12*n) notitle
}
unset multiplot
