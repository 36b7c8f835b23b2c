# instructions per rotated vector of the rotation kernels under callgrind (kept part)
load 'experiments/common/style.gp'
load 'experiments/rotation_kernels/variants.gpi'
set terminal pngcairo size 1500,540 enhanced font ",11"
set output outdir.'/rotation_kernels_instructions.png'
f = outdir.'/instructions.dat'
ids  = "old-zxzxz zxzxz-scalar zxzxz-unrolled zxzxz-avx2 zxzxz-many zxzxz-krot-sse2 zxzxz-krot-avx2 taylor1.5-avx2 old-ivanic ivanic-auto old-blanco blanco-auto"
sel(p, id) = sprintf("< awk '$1 == \"%s\" && $3 == \"%s\"' %s", p, id, f)
set multiplot title "Instructions executed per rotated vector (valgrind callgrind, gcc -O2; AVX-512 cannot run under valgrind)"
set xlabel "order n (bands 0..n−1)"
set xtics ("3" 3, "4" 4, "5" 5, "6" 6, "10" 10)
set xrange [2.6:10.4]
eval logy(10, 100000)
set ylabel "instructions per rotated vector"
set key off
set tmargin at screen 0.87
set bmargin at screen 0.13
set lmargin at screen 0.06
set rmargin at screen 0.37
set title "float"
plot for [i=1:words(ids)] sel("float", word(ids, i)) using 2:8 with linespoints lw 1.5 ps 0.8 \
        lc rgb vcol(word(ids, i)) pt vpt(word(ids, i)) dt vdt(word(ids, i)) notitle
set lmargin at screen 0.44
set rmargin at screen 0.75
set title "double"
set key at screen 0.765, screen 0.87 left top Left reverse samplen 2.5 spacing 1.1 font ",10"
plot for [i=1:words(ids)] sel("double", word(ids, i)) using 2:8 with linespoints lw 1.5 ps 0.8 \
        lc rgb vcol(word(ids, i)) pt vpt(word(ids, i)) dt vdt(word(ids, i)) title vlab(word(ids, i)) noenhanced
unset multiplot
