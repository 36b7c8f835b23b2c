# scene_orders.png: one panel per scene, one line per environment
set terminal pngcairo size 1300,900 enhanced font ",10"
f = outdir.'/scene_orders.dat'
pairs = outdir.'/scene_pairs.txt'
scenes = system("grep -v '^#' ".pairs." | awk '{print $1}' | uniq | tr '\\n' ' '")
envs = system("grep -v '^#' ".pairs." | awk '{print $2}' | awk '!s[$0]++' | tr '\\n' ' '")
NS = words(scenes)
NE = words(envs)
set output outdir.'/scene_orders.png'
# the title from the data file's (the vertex count is the run's)
t = system("sed -n '1s/^# relative L2 shading error vs order/Relative L2 shading error vs SH order/p' ".f)
set multiplot layout 2,2 title t
set logscale y
set format y "10^{%T}"
set yrange [3e-4:2]
set xrange [1:16]
set grid
set xlabel "order n (bands 0..n-1)"
set ylabel "relative L2 shading error"
set key outside right noenhanced font ",8"
set arrow 1 from graph 0, first 0.01 to graph 1, first 0.01 nohead dt 2
set arrow 2 from graph 0, first 0.05 to graph 1, first 0.05 nohead dt 2
do for [s=0:NS-1] {
  set title word(scenes, s+1) noenhanced
  plot for [e=0:NE-1] f index (s*NE+e) using 1:2 with linespoints lw 1.5 pt 7 ps 0.5 title word(envs, e+1)
}
unset multiplot

# scene_rays.png: the transfer's ray count as the error floor
set terminal pngcairo size 800,560 enhanced font ",11"
set output outdir.'/scene_rays.png'
fig = system("grep -v '^#' ".outdir."/scene_fig_name.txt")
set title "Error floor of the transfer's rays (".fig.")" noenhanced
set key inside top right enhanced font ",10"
unset arrow
set arrow 1 from graph 0, first 0.01 to graph 1, first 0.01 nohead dt 2
set arrow 2 from graph 0, first 0.05 to graph 1, first 0.05 nohead dt 2
# the number of ray counts (blocks) of this run
nb = int(system("grep -v '^#' ".outdir."/scene_rays.dat | awk 'NF {print $3}' | sort -u | wc -l"))
plot for [k=0:nb-1] outdir.'/scene_rays.dat' index k using 1:2 with linespoints lw 2 pt 7 ps 0.6 \
     title sprintf("%d rays per vertex", 256*4**k), \
     outdir.'/scene_rays.dat' index nb-1 using 1:4 with lines dt 3 lw 2 lc rgb "#555555" title "reference's own error"

# scene_fig3.png: Křivánek et al. Figure 3 in shading units
set terminal pngcairo size 1200,520 enhanced font ",11"
set output outdir.'/scene_fig3.png'
set multiplot layout 1,2 title "Shading error when the lighting is rotated (".fig.")" noenhanced
set xlabel "β (degrees)"
set xrange [0:90]
set yrange [3e-4:2]
set key inside top left font ",10"
do for [b=0:1] {
  set title sprintf("order %d", b ? 8 : 4)
  plot outdir.'/scene_fig3.dat' index b using 1:2 with linespoints lw 2 pt 7 ps 0.5 lc rgb "#000000" title "exact rotation", \
       '' index b using 1:3 with linespoints lw 2 pt 5 ps 0.5 lc rgb "#1f77b4" title "Taylor 1", \
       '' index b using 1:4 with linespoints lw 2 pt 9 ps 0.6 lc rgb "#2ca02c" title "Taylor 1.5", \
       '' index b using 1:5 with linespoints lw 2 pt 11 ps 0.6 lc rgb "#d62728" title "Taylor 2", \
       '' index b using 1:6 with lines dt 3 lw 2 lc rgb "#888888" title "reference's own error"
}
unset multiplot
