load 'experiments/common/style.gp'
set terminal pngcairo size 1050,540 enhanced font ",11"
set output outdir.'/cap_closed_form.png'
f = outdir.'/cap_quadrature.dat'
eval logy(1e-6, 1e-1)
set xlabel "band l"
set ylabel "|quadrature − closed form| of z_l (absolute)"
set xrange [0:64]
set xtics 0,8,64
eval key_right
set title "Cap light t = 30°: product quadrature of the step against the closed form\n{/*0.85 (4× the nodes: error ÷ 4)}"
# blocks: 5 angles × 4 node counts; t=30° is blocks 4..7
plot for [j=0:3] f index (4+j) using 1:4 with linespoints lt (j+1) lw 1.5 ps 0.5 \
     title sprintf("%s θ nodes", word("64 256 1024 4096", j+1))
