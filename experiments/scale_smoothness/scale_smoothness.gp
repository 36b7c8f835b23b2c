set terminal pngcairo size 1100,480 enhanced font ",11"
set output outdir.'/scale_smoothness_fig3.png'
f = outdir.'/fig3_elements.dat'
labels = system("sed -n '5,$p' ".outdir."/fig3_labels.txt | tr '\\n' ' '")
set multiplot layout 1,2
set xlabel "k = d/r"
set ylabel "M_{ij}(k)"
set logscale x
set xrange [0.5:2]
set xtics (0.5, 0.7, 1, 1.4, 2)
set grid
set key outside bottom center horizontal font ",9"
set title "cone family (θ_0 = 45°), plain, order 4"
plot for [q=1:6] f index 0 using 1:(column(q+1)) with lines lw 2 title word(labels, q) noenhanced
set title "linear family, plain, order 4"
plot for [q=1:6] f index 1 using 1:(column(q+1)) with lines lw 2 title word(labels, q) noenhanced
unset multiplot

set output outdir.'/scale_smoothness_interp.png'
set terminal pngcairo size 1200,430 enhanced font ",11"
f = outdir.'/interp.dat'
set autoscale x
set xtics autofreq
set multiplot layout 1,3
set logscale xy
set format y "10^{%T}"
set xlabel "samples of k"
set ylabel "max |M_{interp} − M|"
set key bottom left font ",9"
do for [b=0:2] {
  set title word("cone_plain linear_plain midrange_energy", b+1) noenhanced
  plot f index b using 1:2 with linespoints pt 7 title "geometric, linear", \
       f index b using 1:4 with linespoints pt 5 title "geometric, cubic", \
       f index b using 1:6 with linespoints pt 9 dt 2 title "uniform, linear", \
       f index b using 1:8 with linespoints pt 11 dt 2 title "uniform, cubic"
}
unset multiplot
