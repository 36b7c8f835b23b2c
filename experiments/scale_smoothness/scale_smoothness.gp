load 'experiments/common/style.gp'
set terminal pngcairo size 1200,520 enhanced font ",11"
set output outdir.'/scale_smoothness_fig3.png'
f = outdir.'/fig3_elements.dat'
labels = system("sed -n '5,$p' ".outdir."/fig3_labels.txt | tr '\\n' ' '")
set multiplot layout 1,2 margins 0.07,0.84,0.13,0.86 spacing 0.08 \
    title "Elements M_{ij}(k) of the scaling matrix over the scale k (Wang et al. Fig. 3 in spirit)"
set xlabel "k = d/r (log scale)"
set ylabel "M_{ij}(k) (dimensionless)"
set logscale x
set xrange [0.5:2]
set xtics (0.5, 0.7, 1, 1.4, 2)
set format x "%g"
unset key
set title "cone family (θ_0 = 45°), plain, order 4"
plot for [q=1:6] f index 0 using 1:(column(q+1)) with linespoints lt q lw 2 ps 0.6 pi 8 notitle
set key at screen 0.85, screen 0.86 left top Left reverse samplen 3 spacing 1.2 title "entry (i, j)" noenhanced
set title "linear family, plain, order 4"
plot for [q=1:6] f index 1 using 1:(column(q+1)) with linespoints lt q lw 2 ps 0.6 pi 8 title word(labels, q) noenhanced
unset multiplot

set output outdir.'/scale_smoothness_interp.png'
set terminal pngcairo size 1450,480 enhanced font ",11"
f = outdir.'/interp.dat'
set multiplot layout 1,3 margins 0.06,0.8,0.14,0.84 spacing 0.06 \
    title "Interpolating M(k) from S tabulated values: largest entry error over k"
eval logx(3, 250)
set xtics (5, 10, 20, 40, 80, 160)
set format x "%g"
eval logy(1e-7, 1)
set xlabel "samples S of k"
set ylabel "max |M_{interp} − M| (absolute)"
unset key
do for [b=0:2] {
  if (b == 2) { set key at screen 0.81, screen 0.84 left top Left reverse samplen 3 spacing 1.2 title "" }
  set title (b == 0 ? "cone family, plain" : b == 1 ? "linear family, plain" : "mid-range family, energy-preserving")
  plot f index b using 1:2 with linespoints lt 1 dt 1 lw 1.5 title "geometric spacing, linear", \
       f index b using 1:4 with linespoints lt 4 dt 1 lw 1.5 title "geometric spacing, cubic", \
       f index b using 1:6 with linespoints lt 1 dt 2 pt 6 lw 1.5 title "uniform spacing, linear", \
       f index b using 1:8 with linespoints lt 4 dt 2 pt 10 lw 1.5 title "uniform spacing, cubic"
  unset key
}
unset multiplot
