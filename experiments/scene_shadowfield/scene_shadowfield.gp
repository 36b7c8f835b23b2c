# sf_orders.png: shadow_rel vs order, one panel per environment
set terminal pngcairo size 1200,520 enhanced font ",11"
envs = system("grep -v '^#' ".outdir."/sf_envs.txt | tr '\\n' ' '")
NE = words(envs)
set output outdir.'/sf_orders.png'
set multiplot layout 1,NE title "Plane shading through the sphere's shadow field: error against the closed form (d0 = H)"
set logscale y
set yrange [1e-3:3]
set xrange [1.5:10.5]
set grid
set xlabel "order n"
set ylabel "shadow\\_rel = |B - B_c| / |B_u - B_c|"
set key top right font ",10"
do for [e=0:NE-1] {
  set title word(envs, e+1) noenhanced
  plot outdir.'/sf_orders.dat' index e using 1:2 with linespoints lw 2 pt 7 lc rgb "#000000" title "exact (fully sampled)", \
       '' index e using 1:3 with linespoints lw 2 pt 5 lc rgb "#1f77b4" title "cone 45°", \
       '' index e using 1:4 with linespoints lw 2 pt 9 lc rgb "#2ca02c" title "cone tangent", \
       '' index e using 1:5 with linespoints lw 2 pt 11 lc rgb "#d62728" title "sphere τ (exact geometry)"
}
unset multiplot

# sf_distance.png: distance bins, sampled distance, moving occluder, k samples
set terminal pngcairo size 1600,460 enhanced font ",10"
set output outdir.'/sf_distance.png'
set multiplot layout 1,4
set key top left font ",9"
set title "receivers' distance (solid: order 4, dashed: 8)"
set xlabel "k = d / d0"
set xrange [1:3]
set yrange [1e-3:3]
plot outdir.'/sf_distance.dat' index 0 using 1:3 with linespoints lw 2 pt 7 lc rgb "#000000" title "exact", \
     '' index 0 using 1:4 with linespoints lw 2 pt 5 lc rgb "#1f77b4" title "cone 45°", \
     '' index 0 using 1:5 with linespoints lw 2 pt 9 lc rgb "#2ca02c" title "cone tangent", \
     '' index 0 using 1:6 with linespoints lw 2 pt 11 lc rgb "#d62728" title "sphere τ", \
     '' index 1 using 1:3 with linespoints lw 1.5 dt 2 pt 7 lc rgb "#000000" notitle, \
     '' index 1 using 1:4 with linespoints lw 1.5 dt 2 pt 5 lc rgb "#1f77b4" notitle, \
     '' index 1 using 1:5 with linespoints lw 1.5 dt 2 pt 9 lc rgb "#2ca02c" notitle, \
     '' index 1 using 1:6 with linespoints lw 1.5 dt 2 pt 11 lc rgb "#d62728" notitle
set title "sampled distance d0 (receivers at d = 1 … 3)"
set xlabel "d0"
set xrange [0.9:3.1]
plot outdir.'/sf_d0.dat' index 0 using 1:2 with linespoints lw 2 pt 7 lc rgb "#000000" title "exact", \
     '' index 0 using 1:3 with linespoints lw 2 pt 5 lc rgb "#1f77b4" title "cone 45°", \
     '' index 0 using 1:4 with linespoints lw 2 pt 9 lc rgb "#2ca02c" title "cone tangent", \
     '' index 0 using 1:5 with linespoints lw 2 pt 11 lc rgb "#d62728" title "sphere τ", \
     '' index 1 using 1:2 with linespoints lw 1.5 dt 2 pt 7 lc rgb "#000000" notitle, \
     '' index 1 using 1:3 with linespoints lw 1.5 dt 2 pt 5 lc rgb "#1f77b4" notitle, \
     '' index 1 using 1:4 with linespoints lw 1.5 dt 2 pt 9 lc rgb "#2ca02c" notitle, \
     '' index 1 using 1:5 with linespoints lw 1.5 dt 2 pt 11 lc rgb "#d62728" notitle
set title "moving sphere, field sampled once at d0 = 1"
set xlabel "sphere height H"
set xrange [0.7:3.1]
set yrange [0.01:5]
plot outdir.'/sf_moving.dat' index 0 using 1:2 with linespoints lw 2 pt 7 lc rgb "#000000" title "exact", \
     '' index 0 using 1:3 with linespoints lw 2 pt 5 lc rgb "#1f77b4" title "cone 45°", \
     '' index 0 using 1:4 with linespoints lw 2 pt 9 lc rgb "#2ca02c" title "cone tangent", \
     '' index 0 using 1:5 with linespoints lw 2 pt 11 lc rgb "#d62728" title "sphere τ", \
     '' index 1 using 1:2 with linespoints lw 1.5 dt 2 pt 7 lc rgb "#000000" notitle, \
     '' index 1 using 1:3 with linespoints lw 1.5 dt 2 pt 5 lc rgb "#1f77b4" notitle, \
     '' index 1 using 1:4 with linespoints lw 1.5 dt 2 pt 9 lc rgb "#2ca02c" notitle, \
     '' index 1 using 1:5 with linespoints lw 1.5 dt 2 pt 11 lc rgb "#d62728" notitle
set title "k samples of M(k), linear interpolation"
set xlabel "samples (geometric over k = 1 … 3)"
set ylabel "|B_K - B_{direct}| / |B_{direct}|"
set logscale x
set xrange [1.8:90]
set yrange [1e-6:0.2]
set format y "10^{%T}"
plot outdir.'/sf_samples.dat' index 0 every ::0::8 using 1:2 with linespoints lw 2 pt 5 lc rgb "#1f77b4" title "cone 45°, order 4", \
     '' index 0 every ::0::8 using 1:3 with linespoints lw 2 pt 11 lc rgb "#d62728" title "sphere τ, order 4", \
     '' index 1 every ::0::8 using 1:2 with linespoints lw 1.5 dt 2 pt 5 lc rgb "#1f77b4" title "cone 45°, order 8", \
     '' index 1 every ::0::8 using 1:3 with linespoints lw 1.5 dt 2 pt 11 lc rgb "#d62728" title "sphere τ, order 8", \
     0.01 with lines dt 3 lc rgb "#888888" title "1 %", 0.001 with lines dt 3 lc rgb "#555555" title "0.1 %"
unset multiplot
