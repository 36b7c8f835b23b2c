set terminal pngcairo size 800,520 enhanced font ",11"
set output outdir.'/scene_bounces.png'
f = outdir.'/bounces.dat'
set title "Bowl under constant radiance 1, albedo 0.8: radiance added by each bounce"
set xlabel "bounce k (0 = direct light)"
set ylabel "radiance added (mean over vertices)"
set logscale y
set format y "10^{%L}"
set grid
set key top right
plot f using 1:3 with lines lw 2 dt 2 lc rgb "#000000" title "closed form (ρ/2)^{k+1}", \
     f using 1:2 with points pt 7 ps 1.3 lc rgb "#d62728" title "measured (transfer, 4096 rays)"
