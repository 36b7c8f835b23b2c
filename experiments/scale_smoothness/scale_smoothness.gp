set terminal pngcairo size 1100,520 enhanced font ",11"
set output outdir.'/scale_smoothness_fig3.png'
f = outdir.'/fig3_elements.dat'
labels = system("sed -n '5,$p' ".outdir."/fig3_labels.txt | tr '\\n' ' '")
cols = "#4E79A7 #F28E2B #E15759 #76B7B2 #59A14F #B07AA1"
set multiplot layout 1,2 margins 0.07,0.98,0.24,0.86 spacing 0.08 \
    title "Elements M_{ij}(k) of the scaling matrix over the scale k (Wang et al. Fig. 3 in spirit)"
set xlabel "k = d/r"
set ylabel "M_{ij}(k)"
set logscale x
set xrange [0.5:2]
set xtics (0.5, 0.7, 1, 1.4, 2)
set grid lc rgb "#dddddd"
unset key
set title "cone family (θ_0 = 45°), plain, order 4"
plot for [q=1:6] f index 0 using 1:(column(q+1)) with lines lw 2 lc rgb word(cols, q) title word(labels, q) noenhanced
set key at screen 0.5, screen 0.02 center bottom horizontal maxrows 2 width 2 font ",10"
set title "linear family, plain, order 4"
plot for [q=1:6] f index 1 using 1:(column(q+1)) with lines lw 2 lc rgb word(cols, q) title word(labels, q) noenhanced
unset multiplot

set output outdir.'/scale_smoothness_interp.png'
set terminal pngcairo size 1200,470 enhanced font ",11"
f = outdir.'/interp.dat'
set xrange [3:250]
set xtics autofreq
set multiplot layout 1,3 margins 0.06,0.98,0.14,0.84 spacing 0.06 \
    title "Interpolating M(k) from S tabulated values: largest entry error over k"
set logscale xy
set format y "10^{%T}"
set format x "%g"
set xlabel "samples S of k"
set ylabel "max |M_{interp} − M|"
unset key
do for [b=0:2] {
  if (b == 2) { set key default; set key inside top right font ",9" samplen 2.5 }
  set title (b == 0 ? "cone family, plain" : b == 1 ? "linear family, plain" : "mid-range family, energy-preserving")
  plot f index b using 1:2 with linespoints lw 1.5 pt 7 lc rgb "#4E79A7" title "geometric spacing, linear", \
       f index b using 1:4 with linespoints lw 1.5 pt 5 lc rgb "#E15759" title "geometric spacing, cubic", \
       f index b using 1:6 with linespoints lw 1.5 pt 9 dt 2 lc rgb "#4E79A7" title "uniform spacing, linear", \
       f index b using 1:8 with linespoints lw 1.5 pt 11 dt 2 lc rgb "#E15759" title "uniform spacing, cubic"
}
unset multiplot
