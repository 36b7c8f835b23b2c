set terminal pngcairo size 1000,520 enhanced font ",11"
set output outdir.'/cap_closed_form.png'
f = outdir.'/cap_quadrature.dat'
set logscale y
set format y "10^{%T}"
set xlabel "band l"
set ylabel "|quadrature − closed form| of z_l"
set xrange [0:64]
set xtics 0,8,64
set grid lc rgb "#dddddd"
set key at screen 0.5, screen 0.01 center bottom horizontal samplen 2.5
set bmargin 5.5
set title "Cap light t = 30°: product quadrature of the step against the closed form (4× the nodes: error ÷ 4)"
cols = "#4E79A7 #F28E2B #59A14F #E15759"
# blocks: 5 angles × 4 node counts; t=30° is blocks 4..7
plot for [j=0:3] f index (4+j) using 1:($4>0?$4:1e-17) with linespoints lw 1.5 pt 7 ps 0.4 lc rgb word(cols, j+1) \
     title sprintf("%s θ nodes", word("64 256 1024 4096", j+1))
