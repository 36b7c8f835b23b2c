# error against counted multiplications per rotation (deterministic)
load 'experiments/common/style.gp'
f = outdir.'/frontier.dat'
names = system("sed -n '5,$p' ".outdir."/methods.txt | tr '\\n' ' '")
betas = "5 15 25"
do for [meas in "lobe max"] {
    set terminal pngcairo size 1400,520 enhanced font ",10"
    set output outdir.'/rotation_frontier_'.meas.'.png'
    col = (meas eq "lobe") ? 7 : 8
    set multiplot layout 1,3 margins 0.06,0.87,0.13,0.86 spacing 0.06 \
        title meas." error against multiplications per rotation (counted; set + apply), orders 4–12 joined, errors below 10^{-17} drawn at 10^{-17}"
    set logscale xy
    set format y "10^{%T}"
    set format x "10^{%T}"
    set xlabel "multiplications per rotation"
    set ylabel meas." error"
    set yrange [5e-18:(meas eq "lobe" ? 10 : 100)]
    set ytics 1e-16,100,1
    unset key
    do for [b=0:2] {
        set title "β = ".word(betas, b+1)."°"
        if (b == 2) { set key at screen 0.995, screen 0.84 right top Left reverse samplen 2.5 font ",10" }
        plot for [i=0:words(names)-1] f index i every :::b::b using 4:col with linespoints lw 1.5 ps 0.6 \
            lc rgb mcol(word(names, i+1)) pt mpt(word(names, i+1)) dt mdt(word(names, i+1)) title word(names, i+1) noenhanced
    }
    unset multiplot
}
