# time per rotated vector of the rotation kernels (timing part): medians with
# quartile bars, and the paired speed-up over the old path
load 'experiments/common/style.gp'
set terminal pngcairo size 1800,560 enhanced font ",11"
set output outdir.'/rotation_kernels.png'
f = outdir.'/kernels.dat'
# the variants drawn, their labels, colours (style.gp's Tableau 10), points, dashes
ids  = "old-zxzxz zxzxz-scalar zxzxz-unrolled zxzxz-avx2 zxzxz-avx512 zxzxz-many zxzxz-krot-avx2 zxzxz-krot-avx512 taylor1.5-avx512 ivanic-auto blanco-auto"
labs = "old:_zxzxz_loops,_angles zxzxz_loops,_matrix zxzxz_unrolled zxzxz_AVX2 zxzxz_AVX-512 zxzxz_apply+many_(256_vectors) zxzxz_256_rotations,_AVX2 zxzxz_256_rotations,_AVX-512 taylor1.5_AVX-512 ivanic,_matrix_(auto) blanco,_matrix"
cols = "#000000 #E15759 #F28E2B #4E79A7 #76B7B2 #59A14F #B07AA1 #9C755F #D37295 #EDC948 #7F7F7F"
pts  = "1 7 5 9 11 13 4 6 8 10 12"
dts  = "1 1 1 1 1 1 1 1 2 3 3"
lab(i) = system("echo '".word(labs, i)."' | tr _+ ' _'")
sel(p, id) = sprintf("< awk '$1 == \"%s\" && $3 == \"%s\"' %s", p, id, f)
noisy = system("awk '!/^#/ && $3 == 1 { c++ } !/^#/ { t++ } END { if (c) printf \"%d of %d runs\", c, t }' ".outdir."/noise.dat")
set multiplot title "rotation kernels, per rotated vector: medians of interleaved samples, bars from quartile 1 to 3 (gcc -O2)"
set xlabel "order n (bands 0..n−1)"
set xtics ("3" 3, "4" 4, "5" 5, "6" 6, "10" 10)
set xrange [2.6:10.4]
set logscale y
set ylabel "ns per rotated vector"
set yrange [0.5:20000]
set format y "10^{%T}"
if (strlen(noisy) > 0) {
    set label 99 "NOISY (".noisy."): compare only\nthe paired speed-ups" at graph 0.03, graph 0.94 left tc rgb "#C00000" font ",10" front
}
set key off
set tmargin at screen 0.88
set bmargin at screen 0.12
set lmargin at screen 0.045
set rmargin at screen 0.30
set title "float"
plot for [i=1:words(ids)] sel("float", word(ids, i)) using 2:10:9:11 with yerrorlines lw 1.5 ps 0.8 \
        lc rgb word(cols, i) pt int(word(pts, i)) dt int(word(dts, i)) notitle
set lmargin at screen 0.355
set rmargin at screen 0.61
set title "double"
plot for [i=1:words(ids)] sel("double", word(ids, i)) using 2:10:9:11 with yerrorlines lw 1.5 ps 0.8 \
        lc rgb word(cols, i) pt int(word(pts, i)) dt int(word(dts, i)) notitle
unset label 99
set lmargin at screen 0.665
set rmargin at screen 0.83
set title "float: paired speed-up over the old path (dashed: 4×)"
set ylabel "t(old zxzxz) / t(variant), median of the rounds"
set yrange [0.1:300]
set format y "%g"
set key at screen 0.84, screen 0.88 left top Left reverse samplen 2.5 spacing 1.1 font ",10"
set arrow 1 from 2.6, 4 to 10.4, 4 nohead dt 2 lw 1.5 lc rgb "#444444"
plot for [i=1:words(ids)] sel("float", word(ids, i)) using 2:14:15:16 with yerrorlines lw 1.5 ps 0.8 \
        lc rgb word(cols, i) pt int(word(pts, i)) dt int(word(dts, i)) title lab(i) noenhanced
unset multiplot
