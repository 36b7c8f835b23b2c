load 'experiments/common/style.gp'
set terminal pngcairo size 1100,780 enhanced font ",11"
set output outdir.'/green_vector.png'
f = outdir.'/green_vector.dat'
set multiplot layout 2,1 margins 0.09,0.8,0.08,0.9 spacing 0,0.12 \
    title "Green (2003) Figure 7 light, 4 bands: printed vs exact vs Monte Carlo (10,000 samples, 400 seeds)"
set xrange [-0.5:15.5]
set xtics 1
unset xlabel
unset title
set ylabel "coefficient value (dimensionless)"
set key at screen 0.81, screen 0.9 left top Left reverse samplen 2 spacing 1.2
plot f using 1:5 with points pt 6 ps 1.8 lc rgb ccol(1) title "exact", \
     f using 1:4 with points pt 2 ps 1.4 lc rgb ccol(4) title "printed (Green)"
# the deviations in units of the Monte Carlo estimator's standard deviation
set xlabel "coefficient index i = l(l+1)+m"
set title "printed − exact in units of σ of Green's estimator (bars: ±2σ; shaded: ±3σ)"
set ylabel "(printed − exact) / σ (standard deviations)"
set yrange [-4:4]
set ytics -4,1,4
set style fill transparent solid 0.12 noborder
unset key
clip(z) = z < -3.8 ? -3.8 : z > 3.8 ? 3.8 : z
plot 3 with filledcurves y1=-3 lc rgb ccol(1) notitle, \
     f using 1:(0):(2) with yerrorbars pt 0 lw 1.5 lc rgb "#999999" notitle, \
     f using 1:(strcol(9) eq "reproduced" ? $8 : 1/0) with points pt 7 ps 1.2 lc rgb ccol(4), \
     f using 1:(strcol(9) eq "reproduced" ? $8 : 1/0):(sprintf("%.2f", $8)) with labels offset 0,0.9 font ",8", \
     f using 1:(strcol(9) eq "differs(sign)" ? clip($8) : 1/0) with points pt 11 ps 1.6 lc rgb ccol(4), \
     f using 1:(strcol(9) eq "differs(sign)" ? clip($8) : 1/0):(sprintf("%.0fσ\n(sign)", $8)) with labels offset 0,1.6 font ",8", \
     f using 1:(strcol(9) eq "missing" ? 0 : 1/0):("not\nprinted") with labels font ",8"
unset multiplot
