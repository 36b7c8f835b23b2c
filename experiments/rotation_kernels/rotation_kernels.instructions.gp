# instructions per rotated vector of the rotation kernels under callgrind (kept part)
load 'experiments/common/style.gp'
set terminal pngcairo size 1500,520 enhanced font ",11"
set output outdir.'/rotation_kernels_instructions.png'
f = outdir.'/instructions.dat'
ids  = "old-zxzxz zxzxz-scalar zxzxz-unrolled zxzxz-avx2 zxzxz-many zxzxz-krot-sse2 zxzxz-krot-avx2 taylor1.5-avx2 old-ivanic ivanic-auto old-blanco blanco-auto"
labs = "old:_zxzxz_loops,_angles zxzxz_loops,_matrix zxzxz_unrolled zxzxz_AVX2 zxzxz_apply+many_(256_vectors) zxzxz_256_rotations,_SSE2 zxzxz_256_rotations,_AVX2 taylor1.5_AVX2 old:_ivanic_loops,_angles ivanic,_matrix_(auto) old:_blanco_loops,_angles blanco,_matrix"
cols = "#000000 #E15759 #F28E2B #4E79A7 #59A14F #BAB0AC #B07AA1 #D37295 #EDC948 #EDC948 #7F7F7F #7F7F7F"
pts  = "1 7 5 9 13 3 4 8 2 10 1 12"
dts  = "1 1 1 1 1 1 1 2 4 3 4 3"
lab(i) = system("echo '".word(labs, i)."' | tr _+ ' _'")
sel(p, id) = sprintf("< awk '$1 == \"%s\" && $3 == \"%s\"' %s", p, id, f)
set multiplot title "instructions executed per rotated vector (valgrind callgrind, gcc -O2; AVX-512 cannot run under valgrind)"
set xlabel "order n (bands 0..n−1)"
set xtics ("3" 3, "4" 4, "5" 5, "6" 6, "10" 10)
set xrange [2.6:10.4]
set logscale y
set ylabel "instructions per rotated vector"
set yrange [10:100000]
set format y "10^{%T}"
set key off
set tmargin at screen 0.88
set bmargin at screen 0.12
set lmargin at screen 0.06
set rmargin at screen 0.40
set title "float"
plot for [i=1:words(ids)] sel("float", word(ids, i)) using 2:8 with linespoints lw 1.5 ps 0.8 \
        lc rgb word(cols, i) pt int(word(pts, i)) dt int(word(dts, i)) notitle
set lmargin at screen 0.47
set rmargin at screen 0.81
set title "double"
set key at screen 0.825, screen 0.88 left top Left reverse samplen 2.5 spacing 1.1 font ",10"
plot for [i=1:words(ids)] sel("double", word(ids, i)) using 2:8 with linespoints lw 1.5 ps 0.8 \
        lc rgb word(cols, i) pt int(word(pts, i)) dt int(word(dts, i)) title lab(i) noenhanced
unset multiplot
