set terminal pngcairo size 1000,560 enhanced font ",11"
set output outdir.'/cap_closed_form.png'
f = outdir.'/cap_quadrature.dat'
set logscale y
set format y "10^{%T}"
set xlabel "band l"
set ylabel "|quadrature − closed form|"
set key outside right
set title "Cap light t = 30°: product quadrature of the step vs the closed form"
# blocks: 5 angles × 4 node counts; t=30° is blocks 4..7
plot for [j=0:3] f index (4+j) using 1:($4>0?$4:1e-17) with linespoints pt 7 ps 0.4 title sprintf("%s θ nodes", word("64 256 1024 4096", j+1))
