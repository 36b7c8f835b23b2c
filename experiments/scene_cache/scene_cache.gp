# cache_a.png: the cache's errors against the allowed error a, one panel per scene × order
set terminal pngcairo size 1200,900 enhanced font ",11"
f = outdir.'/cache_a.dat'
scenes = system("grep -v '^#' ".outdir."/cache_noise.dat | awk '{print $1}' | tr '\\n' ' '")
NS = words(scenes)
set output outdir.'/cache_a.png'
set multiplot layout NS,2 title "Radiance cache: relative L2 error of the luminance over every vertex against the allowed error a"
set logscale xy
set format y "10^{%T}"
set xrange [0.04:0.6]
set xtics ("0.05" 0.05, "0.1" 0.1, "0.2" 0.2, "0.3" 0.3, "0.5" 0.5)
set yrange [1e-6:1]
set grid
set xlabel "allowed error a"
set ylabel "relative L2 error"
set key bottom right font ",9"
do for [s=1:NS] {
  sc = word(scenes, s)
  noise = real(system("grep -v '^#' ".outdir."/cache_noise.dat | awk '$1 == \"".sc."\" {print $2}'"))
  do for [o in "6 10"] {
    set title sc." — order ".o noenhanced
    plot f using 3:((strcol(1) eq sc && $2 == int(o)) ? $8 : 1/0) with linespoints lw 2 pt 7 lc rgb "#000000" title "interpolation (exact rotation) vs direct", \
         f using 3:((strcol(1) eq sc && $2 == int(o)) ? $10 : 1/0) with linespoints lw 2 pt 6 lc rgb "#888888" title "no rotation (ignore) vs direct", \
         f using 3:((strcol(1) eq sc && $2 == int(o)) ? $11 : 1/0) with linespoints lw 2 pt 5 lc rgb "#1f77b4" title "taylor1 vs exact rotation", \
         f using 3:((strcol(1) eq sc && $2 == int(o)) ? $12 : 1/0) with linespoints lw 2 pt 9 lc rgb "#2ca02c" title "taylor1.5 vs exact rotation", \
         f using 3:((strcol(1) eq sc && $2 == int(o)) ? $13 : 1/0) with linespoints lw 2 pt 11 lc rgb "#d62728" title "taylor2 vs exact rotation", \
         noise with lines dt 2 lw 1.5 lc rgb "#555555" title "direct computation's noise (order 6)"
  }
}
unset multiplot
