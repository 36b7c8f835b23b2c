f = outdir.'/frontier.dat'
names = system("sed -n '5,$p' ".outdir."/methods.txt | tr '\\n' ' '")
betas = "5 15 25"
do for [meas in "lobe max"] {
    set terminal pngcairo size 1300,460 enhanced font ",10"
    set output outdir.'/rotation_frontier_'.meas.'.png'
    col = (meas eq "lobe") ? 8 : 9
    set multiplot layout 1,3 title meas." error (clipped at 1e-17) against ns per rotation, orders 4-12 (points joined by order)"
    set logscale xy
    set grid
    set xlabel "ns per rotation (3×3 matrix → set → apply)"
    set ylabel meas." error"
    set yrange [5e-18:10]
    set key bottom right font ",8"
    do for [b=0:2] {
        set title "β = ".word(betas, b+1)."°"
        plot for [i=0:words(names)-1] f index i every :::b::b using 4:col with linespoints pt 7 ps 0.5 title word(names, i+1) noenhanced
    }
    unset multiplot
}
