set terminal pngcairo size 1200,760 enhanced font ",10"
set logscale y
set format y "10^{%T}"
set grid
set key bottom right font ",8"
set xlabel "k"
set ylabel "relative L2 error"

do for [sc in "sphere cone"] {
  set output outdir.'/scale_scenes_'.sc.'.png'
  f = outdir.'/'.sc.'.dat'
  set multiplot layout 2,2 title (sc eq "sphere" ? "Sphere occluder ρ = r/2: scaled from d = r" : "Cone occluder θ_0 = 45°, non-zonal rim: scaled from d = r")
  set logscale x
  set autoscale xfix
  set xtics (0.5, 0.7, 1, 1.4, 2, 2.5)
  set yrange [1e-17:10]
  do for [o=0:3] {
    set title sprintf("order %d", 2+2*o)
    plot f index o using 1:(($3==0&&$4==0)?$5:1/0) with lines lw 2 lc 1 title "linear plain", \
         f index o using 1:(($3==0&&$4==1)?$5:1/0) with lines lw 2 lc 2 title "linear energy", \
         f index o using 1:(($3==1&&$4==0)?$5:1/0) with lines lw 2 lc 3 title "cone plain", \
         f index o using 1:(($3==1&&$4==1)?$5:1/0) with lines lw 2 lc 4 title "cone energy", \
         f index o using 1:(($3==0&&$4==0)?($6>1e-17?$6:1e-17):1/0) with lines dt 2 lc 1 title "geometry: linear plain", \
         f index o using 1:(($3==1&&$4==0)?($6>1e-17?$6:1e-17):1/0) with lines dt 2 lc 3 title "geometry: cone plain", \
         f index o using 1:(($3==1&&$4==1)?$6:1/0) with lines dt 2 lc 4 title "geometry: cone energy"
  }
  unset multiplot
  unset logscale x
  set xtics autofreq
}

probes = system("grep -qi skipped ".outdir."/probe.dat && echo midrange midrange_tilted || echo 'midrange midrange_tilted probe'")
do for [sc in probes] {
  set output outdir.'/scale_scenes_'.sc.'.png'
  f = outdir.'/'.sc.'.dat'
  set terminal pngcairo size 1000,420 enhanced font ",10"
  set multiplot layout 1,2 title (sc eq "midrange" ? "Mid-range lighting (two lobes on a sphere of radius R), centre → d = kR along +z" : sc eq "midrange_tilted" ? "The same lobes, centre → d = kR along (θ,φ) = (60°,135°): rotate to the axis, scale, rotate back" : "Mid-range lighting from an HDR probe, centre → d = kR")
  set yrange [1e-17:10]
  set autoscale xfix
  set title "plain (ψ = sin θ)"
  plot for [o=0:3] f index o using 1:($4==0?$5:1/0) with linespoints pt 7 ps 0.4 title sprintf("order %d", 2+2*o), \
       f index 3 using 1:($4==0?($6>1e-17?$6:1e-17):1/0) with lines dt 2 lc rgb "black" title "geometry (untruncated)"
  set title "energy-preserving (ψ = sin τ·τ')"
  plot for [o=0:3] f index o using 1:($4==1?$5:1/0) with linespoints pt 7 ps 0.4 title sprintf("order %d", 2+2*o), \
       f index 3 using 1:($4==1?$6:1/0) with lines dt 2 lc rgb "black" title "geometry (untruncated)"
  unset multiplot
  set terminal pngcairo size 1200,760 enhanced font ",10"
}

set output outdir.'/scale_scenes_images.png'
set terminal pngcairo size 1200,700 enhanced font ",9"
unset logscale
unset grid
unset key
unset xlabel
unset ylabel
set format y "%g"
set yrange [*:*] reverse
set xrange [*:*]
unset xtics
unset ytics
set multiplot layout 4,4
set palette defined (-0.3 "#2166ac", 0 "white", 1 "#b2182b")
set cbrange [-0.3:1.1]
ks = "0.75 1.3 2"
do for [q=0:2] { set title "cone occluder, exact, k = ".word(ks,q+1); plot outdir.sprintf('/img_cone_exact_%d.dat', q) matrix with image }
set multiplot next
do for [q=0:2] { set title "cone-family scaling, order 8, k = ".word(ks,q+1); plot outdir.sprintf('/img_cone_scaled_%d.dat', q) matrix with image }
set multiplot next
do for [q=0:2] { set title "linear-family scaling, order 8, k = ".word(ks,q+1); plot outdir.sprintf('/img_cone_linear_%d.dat', q) matrix with image }
set multiplot next
set palette defined (0 "black", 0.5 "#d95f02", 1 "#ffff99")
set cbrange [0:1.6]
set title "mid-range k = 0.7, exact"
plot outdir.'/img_mid_exact.dat' matrix with image
set title "exact, order-8 projection"
plot outdir.'/img_mid_exact_proj.dat' matrix with image
set title "plain scaling of centre capture"
plot outdir.'/img_mid_plain.dat' matrix with image
set title "energy-preserving scaling"
plot outdir.'/img_mid_energy.dat' matrix with image
unset multiplot

set output outdir.'/scale_scenes_tilted_images.png'
set terminal pngcairo size 1200,220 enhanced font ",9"
set multiplot layout 1,4 title "mid-range k = 0.7 along (θ,φ) = (60°,135°), order 8 (lat-long, θ down)"
set title "exact"
plot outdir.'/img_tilt_exact.dat' matrix with image
set title "exact, order-8 projection"
plot outdir.'/img_tilt_exact_proj.dat' matrix with image
set title "plain: rotate, scale, rotate back"
plot outdir.'/img_tilt_plain.dat' matrix with image
set title "energy-preserving"
plot outdir.'/img_tilt_energy.dat' matrix with image
unset multiplot
