# time per rotated vector (timing part): medians with quartile bars
load 'experiments/common/style.gp'
set terminal pngcairo size 1400,520 enhanced font ",11"
set output outdir.'/rotation_speed.png'
f = outdir.'/speed.dat'
names = system("sed -n '5,$p' ".outdir."/../methods.txt | tr '\\n' ' '")." zxzxz_dense matrix_to_angles"
nm = words(names) - 2
# a run that broke the noise criterion says so on the figure (left panel, below the data)
noisy = system("awk '!/^#/ { t++; if ($2 == 1) { c++; s = s (c > 1 ? \", \" : \"\") $1 } } END { if (c == t && c) print \"all orders\"; else if (c) print \"orders \" s }' ".outdir."/noise.dat")
if (strlen(noisy) > 0) {
    set label 99 "NOISY RUN (".noisy.")\ndo not compare these times" at graph 0.5, graph 0.1 center tc rgb "#C00000" font ",11" front
}
set multiplot layout 1,2 title "time per rotated vector: medians of interleaved samples, bars from quartile 1 to 3"
set logscale y
set format y "10^{%T}"
set xlabel "order n (bands 0..n−1)"
set ylabel "ns per rotated vector"
set xrange [1.5:16.5]
set xtics 2,2,16
set key outside right top Left reverse samplen 2.5 spacing 1.05 font ",10"
set title "per rotation (3×3 matrix → angles → set → apply)"
plot for [i=0:words(names)-1] f index i every :::0::0 using 2:6:5:7 with yerrorlines lw 1.5 ps 0.7 \
        lc rgb mcol(word(names, i+1)) pt mpt(word(names, i+1)) dt mdt(word(names, i+1)) \
        title mlab(word(names, i+1)) noenhanced
set title "batched (one set, 3 vectors; per vector)"
unset label 99
plot for [i=0:nm-1] f index i every :::1::1 using 2:6:5:7 with yerrorlines lw 1.5 ps 0.7 \
        lc rgb mcol(word(names, i+1)) pt mpt(word(names, i+1)) dt mdt(word(names, i+1)) \
        title mlab(word(names, i+1)) noenhanced
unset multiplot
