set terminal pngcairo size 1000,560 enhanced font ",11"
set output outdir.'/scale_sparsity.png'
f = outdir.'/sparsity.dat'
set xlabel "order N"
set ylabel "non-zeros / N(2N²+1)/3"
set key outside right
set grid
set title "Non-zero entries of the SH scaling matrix relative to the pattern bound"
labels = system("sed -n '5,$p' ".outdir."/sparsity_cases.txt | tr ' ' '_' | tr '\\n' ' '")
plot for [c=0:10] f using 1:(column(3+2*c)/$2) with linespoints pt 7 ps 0.5 title word(labels, c+1) noenhanced
