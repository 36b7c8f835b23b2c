# scene_shading.gp (also the full part: scene_shading.full.gp loads it)
load 'experiments/common/style.gp'

# scene_orders.png: one panel per scene, one line per environment (style.gp's
# cycle), the 1 % and 5 % budgets labelled, one legend for all panels
f = outdir.'/scene_orders.dat'
pairs = outdir.'/scene_pairs.txt'
scenes = system("grep -v '^#' ".pairs." | awk '{print $1}' | uniq | tr '\\n' ' '")
envs = system("grep -v '^#' ".pairs." | awk '{print $2}' | awk '!s[$0]++' | tr '\\n' ' '")
NS = words(scenes)
NE = words(envs)
set terminal pngcairo size 1300,900 enhanced font ",10"
set output outdir.'/scene_orders.png'
# the title from the data file's (the vertex count is the run's)
t = system("sed -n '1s/^# relative L2 shading error vs order/Relative L2 shading error against the SH order/p' ".f)
set multiplot layout 2,2 margins 0.07,0.8,0.08,0.91 spacing 0.08,0.11 title t font ",11"
eval logy(3e-4, 2)
set xrange [1:16]
set xtics 2
set xlabel "order n (bands 0..n−1)"
set ylabel "relative L2 shading error (against the reference)"
eval budget(91, 0.01, "budget 1 %")
eval budget(92, 0.05, "5 %")
unset key
do for [s=0:NS-1] {
  set title word(scenes, s+1) noenhanced
  if (s == NS - 1) { set key at screen 0.815, screen 0.91 left top Left reverse samplen 3 spacing 1.2 font ",10" title "environment" }
  plot for [e=0:NE-1] f index (s*NE+e) using 1:2 with linespoints lt (e+1) lw 1.6 ps 0.6 title word(envs, e+1) noenhanced
  unset key
}
unset multiplot

# scene_rays.png: the transfer's ray count as the error floor
set terminal pngcairo size 900,560 enhanced font ",11"
set output outdir.'/scene_rays.png'
fig = system("grep -v '^#' ".outdir."/scene_fig_name.txt")
set title "Error floor of the transfer's rays (".fig.")" noenhanced
eval key_right
set rmargin 30
eval budgeto(91, 0.01, "1 %")
eval budgeto(92, 0.05, "5 %")
# the number of ray counts (blocks) of this run
nb = int(system("grep -v '^#' ".outdir."/scene_rays.dat | awk 'NF {print $3}' | sort -u | wc -l"))
plot for [k=0:nb-1] outdir.'/scene_rays.dat' index k using 1:2 with linespoints lt (k+1) lw 1.6 ps 0.6 \
     title sprintf("%d rays per vertex", 256*4**k), \
     outdir.'/scene_rays.dat' index nb-1 using 1:4 with lines dt 3 lw 2 lc rgb "#555555" title "reference's own error"

set rmargin
# scene_fig3.png: Křivánek et al. Figure 3 in shading units (the budgets'
# labels back inside the panels: the gap between them has no room)
eval budget(91, 0.01, "budget 1 %")
eval budget(92, 0.05, "5 %")
set terminal pngcairo size 1250,540 enhanced font ",11"
set output outdir.'/scene_fig3.png'
set multiplot layout 1,2 margins 0.07,0.82,0.13,0.86 spacing 0.07 title "Shading error when the lighting is rotated (".fig.")" noenhanced
set xlabel "β (degrees)"
set xrange [0:90]
set xtics 15
unset key
do for [b=0:1] {
  set title sprintf("order %d", b ? 8 : 4)
  if (b == 1) { set key at screen 0.83, screen 0.86 left top Left reverse samplen 3 spacing 1.2 font ",10" title "" }
  plot outdir.'/scene_fig3.dat' index b using 1:2 with linespoints lw 2 ps 0.6 lc rgb mcol("zxzxz") pt mpt("zxzxz") dt 1 title "exact rotation", \
       '' index b using 1:3 with linespoints lw 2 ps 0.6 lc rgb mcol("taylor1") pt mpt("taylor1") dt mdt("taylor1") title "Taylor 1", \
       '' index b using 1:4 with linespoints lw 2 ps 0.6 lc rgb mcol("taylor1.5") pt mpt("taylor1.5") dt mdt("taylor1.5") title "Taylor 1.5", \
       '' index b using 1:5 with linespoints lw 2 ps 0.6 lc rgb mcol("taylor2") pt mpt("taylor2") dt mdt("taylor2") title "Taylor 2", \
       '' index b using 1:6 with lines dt 3 lw 2 lc rgb "#555555" title "reference's own error"
}
unset multiplot
eval nobudget(91)
eval nobudget(92)

# the error pictures with their colour bar (sh_image_colormap, vmax 0.1)
mapsfx = "_error"
errlabel = "|SH − reference| / RMS(reference)"
errmax = 0.1
load 'experiments/common/errormap.gpi'
