set terminal pngcairo size 1000,520 enhanced font ",11"
set output outdir.'/ringing.png'
f = outdir.'/ringing.dat'
set multiplot layout 1,2
set xlabel "order n"
set ylabel "most negative value"
set key bottom right
set grid
do for [s=0:1] {
  set title (s==0 ? "Green's light" : "cap 30°")
  plot for [k=0:3] f index s using 1:($3==k?$4:1/0) with linespoints pt 7 ps 0.6 title word("none gauss hann lanczos", k+1)
}
unset multiplot

set output outdir.'/ringing_images.png'
set terminal pngcairo size 1200,330 enhanced font ",10"
set multiplot layout 1,3
unset grid
unset key
set xlabel "φ"
set ylabel "θ"
set yrange [*:*] reverse
set palette defined (-1 "#2166ac", 0 "white", 1 "#b2182b")
set cbrange [-1.2:1.2]
set xtics ("0" 0, "π" 128, "2π" 255)
set ytics ("0" 0, "π/2" 64, "π" 127)
set title "Green's light"
plot outdir.'/green_original.dat' matrix with image
set title "order 4"
plot outdir.'/green_order4.dat' matrix with image
set title "order 4, Hann window"
plot outdir.'/green_order4_hann.dat' matrix with image
unset multiplot
