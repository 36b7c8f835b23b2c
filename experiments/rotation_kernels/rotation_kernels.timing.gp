# time per rotated vector of the rotation kernels (timing part): medians with
# quartile bars, and the paired speed-up over the old path
load 'experiments/common/style.gp'
set terminal pngcairo size 1800,580 enhanced font ",11"
set output outdir.'/rotation_kernels.png'
f = outdir.'/kernels.dat'
# the variants drawn (their look: variants.gpi)
load 'experiments/rotation_kernels/variants.gpi'
ids  = "old-zxzxz zxzxz-scalar zxzxz-unrolled zxzxz-avx2 zxzxz-avx512 zxzxz-many zxzxz-krot-avx2 zxzxz-krot-avx512 taylor1.5-avx512 ivanic-auto blanco-auto"
sel(p, id) = sprintf("< awk '$1 == \"%s\" && $3 == \"%s\"' %s", p, id, f)
# the NOISY stamp of a panel: from noise.dat, the runs of that precision only
noisy(p) = system(sprintf("awk '!/^#/ && $1 == \"%s\" { t++; if ($3 == 1) { c++; o = o (c > 1 ? \", \" : \"\") $2 } } " . \
                          "END { if (c) printf \"NOISY: %%d of %%d runs (n = %%s): compare\\\\nonly the paired speed-ups\", c, t, o }' %s", \
                          p, outdir.'/noise.dat'))
set multiplot title "Rotation kernels, per rotated vector: medians of interleaved samples, bars from quartile 1 to 3 (gcc -O2; one run per precision and order)"
set xlabel "order n (bands 0..n−1)"
set xtics ("3" 3, "4" 4, "5" 5, "6" 6, "10" 10)
set xrange [2.6:10.4]
eval logy(0.5, 20000)
set ylabel "ns per rotated vector"
set key off
set tmargin at screen 0.86
set bmargin at screen 0.13
set lmargin at screen 0.045
set rmargin at screen 0.28
set title "float"
eval stamp(noisy("float"))
plot for [i=1:words(ids)] sel("float", word(ids, i)) using 2:10:9:11 with yerrorlines lw 1.5 ps 0.8 \
        lc rgb vcol(word(ids, i)) pt vpt(word(ids, i)) dt vdt(word(ids, i)) notitle
set lmargin at screen 0.33
set rmargin at screen 0.565
set title "double"
eval stamp(noisy("double"))
plot for [i=1:words(ids)] sel("double", word(ids, i)) using 2:10:9:11 with yerrorlines lw 1.5 ps 0.8 \
        lc rgb vcol(word(ids, i)) pt vpt(word(ids, i)) dt vdt(word(ids, i)) notitle
set lmargin at screen 0.62
set rmargin at screen 0.80
set title "float: paired speed-up over the old path"
eval stamp(noisy("float"))
set ylabel "t(old zxzxz) / t(variant), median of the rounds"
eval logy(0.1, 300)
set format y "%g"
set key at screen 0.81, screen 0.86 left top Left reverse samplen 2.5 spacing 1.1 font ",10"
eval budget(91, 4, "goal ≥ 4×")
plot for [i=1:words(ids)] sel("float", word(ids, i)) using 2:14:15:16 with yerrorlines lw 1.5 ps 0.8 \
        lc rgb vcol(word(ids, i)) pt vpt(word(ids, i)) dt vdt(word(ids, i)) title vlab(word(ids, i)) noenhanced
unset multiplot
