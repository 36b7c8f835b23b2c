load 'experiments/common/style.gp'
set terminal pngcairo size 950,520 enhanced font ",11"
set output outdir.'/scene_bounces.png'
f = outdir.'/bounces.dat'
set title "Bowl under constant radiance 1, albedo 0.8: radiance added by each bounce"
set xlabel "bounce k (0 = direct light)"
set ylabel "radiance added (mean over vertices)"
stats f using 1 nooutput
set xrange [-0.5:STATS_max + 0.5]
set xtics 1
kmax = STATS_max
eval logy(10.0 ** floor(log10(0.4 ** (kmax + 1))), 1)
eval key_right
plot f using 1:3 with lines lw 2 dt 2 lc rgb "#000000" title "closed form (ρ/2)^{k+1}", \
     f using 1:2 with points pt 7 ps 1.3 lc rgb ccol(4) title "measured (transfer, 4096 rays)"
