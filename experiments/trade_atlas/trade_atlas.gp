# The trade atlas: per precision and path, one panel per β range; in each,
# every order's Pareto frontier of model cost against worst max error, the
# order labelled at its cheapest point, budgets 1e-2 … 1e-12 as dashed verticals.
load 'experiments/common/style.gp'
set terminal pngcairo size 1500,900 enhanced font ",11"
names = system("sed -n '5,$p' ".outdir."/methods.txt | tr '\\n' ' '")
betas = "5 20 45 90 180"
# the orders drawn (the data has every order 2..16)
shown(n) = (n == 2 || n == 3 || n == 4 || n == 6 || n == 8 || n == 12 || n == 16)
do for [pp in "float_per-rotation float_k-rotations double_per-rotation double_k-rotations"] {
    f = outdir.'/atlas_'.pp.'.dat'
    lf = outdir.'/labels_'.pp.'.dat'
    isf = strstrt(pp, "float") > 0
    xlo = isf ? 1e-8 : 1e-16
    set output outdir.'/trade_atlas_'.pp.'.png'
    set multiplot layout 2,3 title sprintf("Rotation: model cost against worst error (max unit), %s, %s from 3×3 matrices", \
        isf ? "float" : "double", strstrt(pp, "k-rotations") ? "256 rotations per call" : "one rotation at a time") font ",13"
    do for [b = 0:4] {
        eval logx(xlo, 1)
        set logscale y
        set autoscale y
        set format y '10^{%T}'
        set ytics autofreq
        set xlabel "worst max error over β ∈ [0, B] (σ_{max} of R − R_{exact})"
        set ylabel "ns per rotated vector (model)"
        set title (b < 4 ? sprintf("β ≤ %s°", word(betas, b + 1)) : "any β")
        unset arrow
        do for [e = 2:12] {
            if (10.0**-e > xlo) { set arrow e from first 10.0**-e, graph 0 to first 10.0**-e, graph 1 nohead dt 3 lw 1 lc rgb '#aaaaaa' back }
        }
        set key off
        plot f index b u (shown($2) ? $4 : NaN):5 w l lc rgb '#b0b0b0' lw 1 notitle, \
             for [m in names] f index b u (shown($2) && strcol(3) eq m ? $4 : NaN):5 w p lc rgb mcol(m) pt mpt(m) ps 1.0 notitle, \
             lf index b u (shown($2) ? $3 : NaN):4:(sprintf("n=%d", $2)) w labels left offset 0.6,0.5 font ",9" tc rgb '#333333' notitle
    }
    # the legend panel
    unset arrow; unset title; unset xlabel; unset ylabel; unset logscale; unset border; unset tics
    set xrange [0:1]; set yrange [0:1]
    set key center center Left reverse font ",11" title "method (dashed verticals: budgets 10^{-2} … 10^{-12})"
    plot for [m in names] NaN w p lc rgb mcol(m) pt mpt(m) ps 1.2 title mlab(m)
    set border; set tics
    unset multiplot
}
