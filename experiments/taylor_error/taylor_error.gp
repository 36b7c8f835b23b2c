# Figure 3 (Křivánek et al. 2005) reproduced: rows max / mean / lobe, columns order 5 / 8.
load 'experiments/common/style.gp'
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
    plot f index o using 1:(column(1+r)) with lines lw 2 lc rgb mcol("taylor1") title 'Taylor 1', \
         f index o using 1:(column(4+r)) with lines lw 2 lc rgb mcol("taylor1.5") title 'Taylor 1.5', \
         f index o using 1:(column(7+r)) with lines lw 2 lc rgb mcol("taylor2") title 'Taylor 2'
  }
}
unset multiplot

set terminal pngcairo size 1300,820 enhanced font ",10"
set output outdir.'/taylor_error_ext.png'
g = outdir.'/extended.dat'
set multiplot layout 2,3 margins 0.06,0.89,0.07,0.91 spacing 0.06,0.14 \
    title "Orders 2–16, β to 90°: lobe error (top) and largest singular value of D (bottom); colour = order"
set yrange [1e-8:1e3]
set ytics 1e-8,100,1e2
set key off
# one colour per order n = 2..16 (sequential palette, the colour bar is the legend)
set palette defined (2 "#fde725", 5 "#5ec962", 9 "#21918c", 12 "#3b528b", 16 "#440154")
set cbrange [2:16]
set cbtics 2,2,16
set cblabel "order n"
unset colorbox
tn = "1 1.5 2"
do for [t=0:2] {
  set title 'Taylor '.word(tn, t+1).': lobe error'
  set ylabel 'lobe error'
  plot for [n=0:14] g index n using 2:(column(5+3*t)):(n+2) with lines lw 1.5 lc palette notitle
}
set colorbox user origin screen 0.91, screen 0.25 size screen 0.015, screen 0.5
do for [t=0:2] {
  set title 'Taylor '.word(tn, t+1).': max σ(D)'
  set ylabel 'max error'
  plot for [n=0:14] g index n using 2:(column(3+3*t)):(n+2) with lines lw 1.5 lc palette notitle
  unset colorbox
}
unset multiplot
