# instructions per rotated vector under callgrind (kept part)
load 'experiments/common/style.gp'
set terminal pngcairo size 1400,540 enhanced font ",11"
set output outdir.'/rotation_speed_instructions.png'
f = outdir.'/instructions.dat'
names = system("sed -n '5,$p' ".outdir."/methods.txt | tr '\\n' ' '")
set multiplot layout 1,2 margins 0.06,0.86,0.13,0.86 spacing 0.08 \
    title "Instructions executed per rotated vector (valgrind callgrind, gcc -O2)"
set xlabel "order n (bands 0..n−1)"
set xtics 2,2,16
set xrange [1.5:16.5]
unset key
eval logy(100, 1e7)
set ylabel "instructions per rotated vector"
set title "per rotation: 3×3 matrix → angles → set → apply"
plot for [i=0:words(names)-1] f index i using 2:3 with linespoints lw 1.5 ps 0.7 \
        lc rgb mcol(word(names, i+1)) pt mpt(word(names, i+1)) dt mdt(word(names, i+1)) notitle
set title "per counted multiplication (the matrix → angles step dominates at low n)"
eval logy(1, 1000)
set format y "%g"
set ylabel "instructions / counted multiplications"
set key at screen 0.87, screen 0.86 left top Left reverse samplen 2.5 spacing 1.1 font ",10"
plot for [i=0:words(names)-1] f index i using 2:6 with linespoints lw 1.5 ps 0.7 \
        lc rgb mcol(word(names, i+1)) pt mpt(word(names, i+1)) dt mdt(word(names, i+1)) \
        title word(names, i+1) noenhanced
unset multiplot
