# scene_shadowfield.gp (also the probes part: scene_shadowfield.probes.gp loads it)
load 'experiments/common/style.gp'
envs = system("grep -v '^#' ".outdir."/sf_envs.txt | tr '\\n' ' '")
NE = words(envs)
# one look per field in both figures (style.gp's cycle)
fl(j) = word("exact_(fully_sampled) cone_45° cone_tangent sphere_τ_(exact_geometry)", j)
flab(j) = system("echo '".fl(j)."' | tr _ ' '")

# sf_orders.png: shadow_rel against the order, one panel per environment
set terminal pngcairo size 1300,540 enhanced font ",11"
set output outdir.'/sf_orders.png'
set multiplot layout 1,NE margins 0.07,0.78,0.13,0.86 spacing 0.07 \
    title "Plane shading through the sphere's shadow field: error against the closed form (d0 = H)"
eval logy(1e-3, 3)
set xrange [1.5:10.5]
set xtics 2,1,10
set xlabel "order n (bands 0..n−1)"
set ylabel "shadow\\_rel = |B − B_c| / |B_u − B_c|"
unset key
do for [e=0:NE-1] {
  set title word(envs, e+1) noenhanced
  if (e == NE - 1) { set key at screen 0.79, screen 0.86 left top Left reverse samplen 3 spacing 1.25 font ",10" title "field" }
  plot for [j=1:4] outdir.'/sf_orders.dat' index e using 1:(column(j+1)) with linespoints lt j lw 1.8 ps 0.8 title flab(j)
  unset key
}
unset multiplot

# sf_distance.png: distance bins, sampled distance, moving occluder, k samples
# (environment: the first of sf_envs.txt); solid order 4, dashed order 8;
# one legend for the four panels, beside them
set terminal pngcairo size 1750,500 enhanced font ",10"
set output outdir.'/sf_distance.png'
set multiplot title sprintf("Shadow fields under %s: the fields against the receivers' distance, the sampled distance, a moving occluder, and the samples of M(k)", word(envs, 1)) font ",11"
set tmargin at screen 0.84
set bmargin at screen 0.14
P(i) = 0.045 + i * 0.2
eval logy(1e-3, 3)
unset key
set lmargin at screen P(0)
set rmargin at screen P(0) + 0.15
set title "receivers' distance (d0 = H)"
set xlabel "k = d / d0 (receiver's distance over the sampled one)"
set xrange [1:3]
set xtics 0.5
set mxtics 5
plot for [j=1:4] outdir.'/sf_distance.dat' index 0 using 1:(column(j+2)) with linespoints lt j dt 1 lw 1.8 ps 0.7 notitle, \
     for [j=1:4] outdir.'/sf_distance.dat' index 1 using 1:(column(j+2)) with linespoints lt j dt 2 lw 1.4 ps 0.7 notitle
set lmargin at screen P(1)
set rmargin at screen P(1) + 0.15
set title "sampled distance d0 (receivers at d = 1 … 3)"
set xlabel "d0 (scene units; sphere radius 0.5)"
set xrange [0.9:3.1]
plot for [j=1:4] outdir.'/sf_d0.dat' index 0 using 1:(column(j+1)) with linespoints lt j dt 1 lw 1.8 ps 0.7 notitle, \
     for [j=1:4] outdir.'/sf_d0.dat' index 1 using 1:(column(j+1)) with linespoints lt j dt 2 lw 1.4 ps 0.7 notitle
set lmargin at screen P(2)
set rmargin at screen P(2) + 0.15
set title "moving sphere, field sampled once at d0 = 1"
set xlabel "sphere height H (scene units)"
set xrange [0.7:3.1]
eval logy(0.01, 5)
plot for [j=1:4] outdir.'/sf_moving.dat' index 0 using 1:(column(j+1)) with linespoints lt j dt 1 lw 1.8 ps 0.7 notitle, \
     for [j=1:4] outdir.'/sf_moving.dat' index 1 using 1:(column(j+1)) with linespoints lt j dt 2 lw 1.4 ps 0.7 notitle
set lmargin at screen P(3)
set rmargin at screen P(3) + 0.15
set title "k samples of M(k), linear interpolation"
set xlabel "samples of k (geometric over k = 1 … 3)"
set ylabel "|B_K − B_{direct}| / |B_{direct}|"
set logscale x
set xrange [1.8:90]
set xtics ("2" 2, "3" 3, "4" 4, "6" 6, "8" 8, "12" 12, "20" 20, "40" 40, "80" 80)
set mxtics 1
set format x "%g"
eval logy(1e-6, 0.2)
eval budget(91, 0.01, "1 %")
eval budget(92, 0.001, "0.1 %")
set key at screen 0.85, screen 0.84 left top Left reverse samplen 3 spacing 1.25 font ",10" title "field"
plot outdir.'/sf_samples.dat' index 0 every ::0::8 using 1:2 with linespoints lt 2 dt 1 lw 1.8 ps 0.7 notitle, \
     '' index 0 every ::0::8 using 1:3 with linespoints lt 4 dt 1 lw 1.8 ps 0.7 notitle, \
     '' index 1 every ::0::8 using 1:2 with linespoints lt 2 dt 2 lw 1.4 ps 0.7 notitle, \
     '' index 1 every ::0::8 using 1:3 with linespoints lt 4 dt 2 lw 1.4 ps 0.7 notitle, \
     for [j=1:4] NaN with linespoints lt j dt 1 lw 1.8 ps 0.7 title flab(j), \
     NaN with lines lc rgb "#000000" dt 1 lw 1.8 title "order 4 (solid)", \
     NaN with lines lc rgb "#000000" dt 2 lw 1.4 title "order 8 (dashed)"
unset multiplot
eval nobudget(91)
eval nobudget(92)

# the error picture with its colour bar (sh_image_colormap, vmax 0.1)
mapsfx = "_error"
errlabel = "|field − closed form| / RMS"
errmax = 0.1
load 'experiments/common/errormap.gpi'
