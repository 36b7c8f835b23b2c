set terminal pngcairo size 1100,480 enhanced font ",11"
set output outdir.'/rotation_speed.png'
f = outdir.'/speed.dat'
names = system("sed -n '5,$p' ".outdir."/methods.txt | tr '\\n' ' '")
set multiplot layout 1,2
set logscale y
set grid
set xlabel "order n"
set ylabel "ns per rotated vector"
set key top left
set title "per rotation (3×3 matrix → set → apply)"
plot for [i=0:words(names)-1] f index i using (strcol(3) eq "per-rotation" ? $2 : 1/0):4 with linespoints pt 7 ps 0.5 title word(names, i+1) noenhanced, \
     outdir.'/dense_zxzxz.dat' using 1:2 with lines dt 2 lc rgb "gray40" title "zxzxz, dense X (test)"
set title "batched (one set, 3 vectors), per vector"
plot for [i=0:words(names)-1] f index i using (strcol(3) eq "batched" ? $2 : 1/0):4 with linespoints pt 7 ps 0.5 title word(names, i+1) noenhanced
unset multiplot
