# lobe error against time per rotation (timing part)
load 'experiments/common/style.gp'
f = outdir.'/frontier_time.dat'
names = system("sed -n '5,$p' ".outdir."/../methods.txt | tr '\\n' ' '")
betas = "5 15 25"
set terminal pngcairo size 1400,520 enhanced font ",10"
# a run that broke the noise criterion says so on the figure
noisy = system("awk '!/^#/ && NF { t[$3] = 1; if ($12 == 1) o[$3] = 1 } END { for (k in t) { n++; if (k in o) c++ } if (c == n && c) print \"all orders\"; else if (c) print c \" of \" n \" orders\" }' ".outdir."/frontier_time.dat")
if (strlen(noisy) > 0) {
    set label 99 "NOISY RUN (".noisy."): do not compare these times" at screen 0.47, screen 0.5 center tc rgb "#C00000" font ",12" front
}
set output outdir.'/rotation_frontier_lobe_time.png'
set multiplot layout 1,3 margins 0.06,0.87,0.13,0.86 spacing 0.06 \
    title "lobe error against time per rotation (3×3 matrix → set → apply; medians of interleaved samples), orders 4–12 joined"
set logscale xy
set format y "10^{%T}"
set format x "10^{%T}"
set xlabel "ns per rotation"
set ylabel "lobe error"
set yrange [5e-18:10]
set ytics 1e-16,100,1
unset key
do for [b=0:2] {
    set title "β = ".word(betas, b+1)."°"
    if (b == 2) { set key at screen 0.995, screen 0.84 right top Left reverse samplen 2.5 font ",10" }
    plot for [i=0:words(names)-1] f index i every :::b::b using 4:10 with linespoints lw 1.5 ps 0.6 \
        lc rgb mcol(word(names, i+1)) pt mpt(word(names, i+1)) dt mdt(word(names, i+1)) title word(names, i+1) noenhanced
}
unset multiplot
