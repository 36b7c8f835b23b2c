load 'experiments/common/style.gp'
set terminal pngcairo size 1150,520 enhanced font ",11"
set output outdir.'/ringing.png'
f = outdir.'/ringing.dat'
set multiplot layout 1,2 margins 0.08,0.82,0.13,0.85 spacing 0.08 \
    title "Ringing: most negative value of the order-n reconstruction of a non-negative light"
set xlabel "order n (bands 0..n−1)"
set ylabel "most negative value (units of the light; 0 = no ringing)"
set xrange [1.5:16.5]
set xtics 2,2,16
wt(k) = k == 0 ? "no window" : k == 1 ? "Gauss window" : k == 2 ? "Hann window" : "Lanczos window"
unset key
do for [s=0:1] {
  set title (s==0 ? "Green's light" : "cap, half-angle 30°")
  if (s == 1) { set key at screen 0.83, screen 0.85 left top Left reverse samplen 3 spacing 1.2 }
  # rows: per order the four windows in turn
  plot for [k=0:3] f index s every 4::k using 1:4 with linespoints lt (k+1) ps 0.6 lw 1.5 title wt(k)
}
unset multiplot

set output outdir.'/ringing_images.png'
set terminal pngcairo size 1300,330 enhanced font ",10"
set multiplot layout 1,3 margins 0.05,0.92,0.15,0.85 spacing 0.05
set size ratio 0.5
set colorbox user origin screen 0.935, screen 0.2 size screen 0.012, screen 0.6
unset grid
unset key
set xlabel "φ (azimuth)"
set ylabel "θ (polar angle)"
set xrange [-0.5:255.5]

set yrange [127.5:-0.5]
set palette defined (-1 "#2166ac", 0 "white", 1 "#b2182b")
set cbrange [-1.2:1.2]
set cblabel "value of the light (white: 0)" font ",9"
set xtics ("0" 0, "π" 128, "2π" 255)
set ytics ("0" 0, "π/2" 64, "π" 127)
set title "Green's light"
plot outdir.'/green_original.dat' matrix with image
unset colorbox
set title "order 4"
plot outdir.'/green_order4.dat' matrix with image
set title "order 4, Hann window"
plot outdir.'/green_order4_hann.dat' matrix with image
unset multiplot
