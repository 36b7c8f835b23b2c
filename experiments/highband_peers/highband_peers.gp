# memory of one rotation of all bands 0..lmax against lmax (log-log):
# the streamed rotation against the plans that store every band's block
load 'experiments/common/style.gp'
set terminal pngcairo size 1250,640 enhanced font ",11"
set output outdir.'/highband_peers_memory.png'
f = outdir.'/memory.dat'
set title "memory of one rotation of all bands 0..lmax (double precision; sizes from the library)"
set logscale xy
set xrange [90:4500]
set yrange [0.05:5e6]
set ylabel "memory (MB = 10^6 bytes)"
set xtics (100, 200, 300, 500, 1000, 2000, 4000)
set ytics ("0.1 MB" 0.1, "1 MB" 1, "10 MB" 10, "100 MB" 100, "1 GB" 1e3, "10 GB" 1e4, "100 GB" 1e5, "1 TB" 1e6, "10 TB" 1e7)
set xlabel "lmax (bands 0..lmax)"
eval key_right
# the goal for one rotation at lmax 1000 and this machine's 24 GB
set arrow 1 from 90, 64 to 4500, 64 nohead dt 2 lc rgb "#C00000" lw 1.2
set label 1 "64 MB: goal for the peak RSS of one rotation at lmax 1000" at 105, 64*1.6 tc rgb "#C00000" font ",9" front boxed
plot f using 1:11 with linespoints lw 1.8 pt mpt("ivanic") lc rgb mcol("ivanic") title "ivanic plan (stored blocks + recursion)", \
     f using 1:10 with linespoints lw 1.8 pt mpt("blanco") lc rgb mcol("blanco") title "blanco plan (stored blocks)", \
     f using 1:9 with linespoints lw 1.8 pt mpt("zxzxz") lc rgb mcol("zxzxz") title "zxzxz plan (stored X_{±90} blocks)", \
     f using 1:8 with lines lw 1.2 dt 3 lc rgb "#555555" title "blocks of all bands, Σ(2l+1)^2 doubles", \
     f using 1:6 with linespoints lw 2.2 pt 7 ps 0.8 lc rgb "#000000" title "streamed: one rotation (2 vectors + scratch)", \
     f using 1:3 with lines lw 1.2 dt 2 lc rgb ccol(6) title "one coefficient vector, (lmax+1)^2 doubles", \
     f using 1:5 with linespoints lw 1.8 pt 9 lc rgb ccol(9) dt 1 title "streamed: scratch on 2 threads", \
     f using 1:4 with linespoints lw 1.8 pt 8 lc rgb ccol(3) dt 1 title "streamed: scratch on 1 thread"
