# Figure 3 (Křivánek et al. 2005) reproduced: rows max / mean / lobe, columns
# order 5 / 8; β on a log axis, so that the small angles where the expansions
# cross the error budgets (1e-2 between 3° and 9°) are not squeezed together.
load 'experiments/common/style.gp'
set terminal pngcairo size 1150,1200 enhanced font ",10"
set output outdir.'/taylor_error_fig3.png'
f = outdir.'/figure3.dat'
set multiplot layout 3,2 margins 0.08,0.97,0.1,0.93 spacing 0.08,0.07 \
    title "Error of the Taylor-approximated rotation about y (unit vectors; lobe: the unit-length cos^7 lobe)" font ",11"
eval logy(1e-6, 20)
eval logx(0.25, 45)
set xtics ("0.25" 0.25, "0.5" 0.5, "1" 1, "2" 2, "3" 3, "5" 5, "10" 10, "20" 20, "45" 45)
set xlabel "β (degrees, log scale)"
names = "max mean lobe"
what  = "max error σ_{max}(D)|mean error (mean σ of D)|lobe error ‖Dc‖"
orders = "5 8"
unset key
do for [r=1:3] {
  do for [o=0:1] {
    set ylabel system("echo '".what."' | cut -d'|' -f".r)
    set title 'order '.word(orders, o+1)
    eval budget(91, 1e-2, "10^{-2}")
    eval budget(92, 1e-3, "10^{-3}")
    if (r == 3 && o == 1) { eval key_below; set key at screen 0.5, screen 0.02 center bottom horizontal }
    plot f index o using 1:(column(1+r)) with lines lw 2 lc rgb mcol("taylor1") dt mdt("taylor1") title 'Taylor 1', \
         f index o using 1:(column(4+r)) with lines lw 2 lc rgb mcol("taylor1.5") dt mdt("taylor1.5") title 'Taylor 1.5', \
         f index o using 1:(column(7+r)) with lines lw 2 lc rgb mcol("taylor2") dt mdt("taylor2") title 'Taylor 2'
  }
}
unset multiplot
eval nobudget(91)
eval nobudget(92)
unset key

# Orders 2–16, β to 90°: one line per selected order (the cycle's colours,
# points and dashes; orders above 8 coincide with 8 on the lobe row)
set terminal pngcairo size 1400,860 enhanced font ",10"
set output outdir.'/taylor_error_ext.png'
g = outdir.'/extended.dat'
sel = "2 3 4 6 8 12 16"
set multiplot layout 2,3 margins 0.06,0.86,0.08,0.91 spacing 0.06,0.12 \
    title "Orders 2–16, β to 90°: lobe error (top; from n = 6 on the lines coincide) and largest singular value of D (bottom), one line per order n" font ",11"
eval logy(1e-8, 1e3)
eval logx(1, 90)
set xtics ("1" 1, "2" 2, "3" 3, "5" 5, "10" 10, "20" 20, "45" 45, "90" 90)
set xlabel "β (degrees, log scale)"
tn = "1 1.5 2"
do for [row=0:1] {
  do for [t=0:2] {
    set title 'Taylor '.word(tn, t+1).(row ? ': max error σ_{max}(D)' : ': lobe error ‖Dc‖')
    set ylabel (row ? 'max error σ_{max}(D)' : 'lobe error ‖Dc‖ (unit lobe)')
    if (row == 0) { eval budget(91, 1e-2, "10^{-2}"); eval budget(92, 1e-3, "10^{-3}") } else { eval nobudget(91); eval nobudget(92) }
    if (row == 1 && t == 2) { set key at screen 0.875, screen 0.91 left top vertical maxrows 10 Left reverse samplen 3 spacing 1.2 font ",10" title "order n" }
    plot for [k=1:words(sel)] g index (int(word(sel, k)) - 2) using 2:(column(row ? 3+3*t : 5+3*t)) \
            with linespoints lt k lw 1.6 ps 0.6 pi 12 title word(sel, k)
    unset key
  }
}
unset multiplot
