# time per rotated vector (timing part): medians with quartile bars
load 'experiments/common/style.gp'
set terminal pngcairo size 1500,560 enhanced font ",11"
set output outdir.'/rotation_speed.png'
f = outdir.'/speed.dat'
names = system("sed -n '5,$p' ".outdir."/../methods.txt | tr '\\n' ' '")." zxzxz_dense matrix_to_angles"
nm = words(names) - 2
# The noise criterion is judged per order (one interleaved run per order,
# both panels): the orders that broke it, read from noise.dat, are shaded,
# and Table 1's orders (6, 10) are named quiet or noisy from the same data.
nord = system("awk '!/^#/ && NF && $2 == 1 { printf \"%s \", $1 }' ".outdir."/noise.dat")
nordc = system("awk '!/^#/ && NF && $2 == 1 { printf \"%s%s\", n++ ? \", \" : \"\", $1 }' ".outdir."/noise.dat")
t1 = system("awk '!/^#/ && ($1 == 6 || $1 == 10) && $2 == 1 { n++ } END { print n ? \"noisy\" : \"quiet\" }' ".outdir."/noise.dat")
do for [k = 1:words(nord)] {
    o = int(word(nord, k))
    set object 10 + k rect from o - 0.45, graph 0 to o + 0.45, graph 1 behind fc rgb "#ececec" fs solid 1.0 noborder
}
shade = words(nord) > 0 ? sprintf("shaded: orders whose run broke the noise criterion (%s); Table 1's n = 6, 10: %s", nordc, t1) : ""
# The unrolled (generated straight-line) kernels end at the orders of
# ../unrolled.txt (zxzxz and the Taylor methods; ivanic); above, the loop
# kernels run: the steps in the curves.
uz = int(system("awk '!/^#/ && $1 == \"zxzxz\" { print $2 }' ".outdir."/../unrolled.txt"))
ui = int(system("awk '!/^#/ && $1 == \"ivanic\" { print $2 }' ".outdir."/../unrolled.txt"))
set arrow 1 from uz + 0.5, graph 0 to uz + 0.5, graph 1 nohead dt 3 lw 1.2 lc rgb "#444444" back
set label 1 sprintf("unrolled kernels end:\nn ≤ %d unrolled,\nloops above", uz) at uz + 0.65, graph 0.1 left font ",8" tc rgb "#333333" front
set arrow 2 from ui + 0.5, graph 0 to ui + 0.5, graph 1 nohead dt 3 lw 1.2 lc rgb mcol("ivanic") back
set label 2 sprintf("ivanic unrolled\nto n = %d", ui) at ui + 0.35, graph 0.95 right font ",8" tc rgb "#333333" front
set multiplot layout 1,2 margins 0.06,0.80,0.17,0.88 spacing 0.07 \
    title "Time per rotated vector: medians of interleaved samples, bars from quartile 1 to 3 (one run per order)"
eval logy(10, 1e6)
set xlabel "order n (bands 0..n−1)"
set ylabel "ns per rotated vector"
set xrange [1.5:16.5]
set xtics 2,1,16
unset key
set title "per rotation (3×3 matrix → angles → set → apply)"
if (strlen(shade) > 0) { set label 3 shade at screen 0.06, screen 0.045 left font ",9" tc rgb "#555555" }
plot for [i=0:words(names)-1] f index i every :::0::0 using 2:6:5:7 with yerrorlines lw 1.5 ps 0.7 \
        lc rgb mcol(word(names, i+1)) pt mpt(word(names, i+1)) dt mdt(word(names, i+1)) notitle
unset label 3
eval logy(10, 1e5)
set title "batched (one set, 3 vectors; per vector)"
set key at screen 0.81, screen 0.88 left top Left reverse samplen 2.5 spacing 1.05 font ",10"
plot for [i=0:nm-1] f index i every :::1::1 using 2:6:5:7 with yerrorlines lw 1.5 ps 0.7 \
        lc rgb mcol(word(names, i+1)) pt mpt(word(names, i+1)) dt mdt(word(names, i+1)) \
        title mlab(word(names, i+1)) noenhanced, \
     for [i=nm:words(names)-1] NaN with linespoints lw 1.5 ps 0.7 lc rgb mcol(word(names, i+1)) \
        pt mpt(word(names, i+1)) dt mdt(word(names, i+1)) title mlab(word(names, i+1))." (left)" noenhanced
unset multiplot
