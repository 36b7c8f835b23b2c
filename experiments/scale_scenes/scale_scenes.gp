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
  # the sphere's errors stay above 1e-6; the cone's plain geometry is exact (1e-16)
  set yrange [(sc eq "sphere" ? 1e-6 : 1e-17):10]
  do for [o=0:3] {
    if (o == 0) { set key bottom right font ",8" } else { unset key }
    set title sprintf("order %d", 2+2*o)
    # energy-preserving curves of both families nearly coincide: the linear
    # one is drawn wide and light under the cone one
    plot f index o using 1:(($3==0&&$4==1)?$5:1/0) with lines lw 5 lc rgb "#a6d9a0" title "linear energy", \
         f index o using 1:(($3==0&&$4==0)?$5:1/0) with lines lw 2 lc 1 title "linear plain", \
         f index o using 1:(($3==1&&$4==0)?$5:1/0) with lines lw 2 lc 3 title "cone plain", \
         f index o using 1:(($3==1&&$4==1)?$5:1/0) with lines lw 1.5 lc 4 title "cone energy", \
         f index o using 1:(($3==0&&$4==0)?($6>1e-17?$6:1e-17):1/0) with lines dt 2 lc 1 title "geometry: linear plain", \
         f index o using 1:(($3==1&&$4==0)?($6>1e-17?$6:1e-17):1/0) with lines dt 2 lc 3 title "geometry: cone plain", \
         f index o using 1:(($3==1&&$4==1)?$6:1/0) with lines dt 2 lc 4 title "geometry: cone energy"
  }
  unset multiplot
  unset logscale x
  set xtics autofreq
}

do for [sc in "midrange midrange_tilted"] {
  load 'experiments/scale_scenes/midrange.gpi'
}

# Reconstructions as lat-long images (96×48 samples at pixel centres):
# φ = 360°·(column + ½)/96 to the right, θ = 180°·(row + ½)/48 downwards.
unset logscale
unset grid
unset key
set format y "%g"
set format x "%g"
set xrange [0:360]
set yrange [180:0]
set xtics 0,90,360 font ",8" offset 0,0.3
set ytics 0,45,180 font ",8" offset 0.5,0
set mxtics 1
set mytics 1
set xlabel "φ (°)" font ",8" offset 0,1
set ylabel "θ (°)" font ",8" offset 2.5,0
set tics out scale 0.5
set size ratio 0.5
ll = "using (($1+0.5)*3.75):(($2+0.5)*3.75):3 with image"

set output outdir.'/scale_scenes_images.png'
set terminal pngcairo size 1300,860 enhanced font ",9"
set multiplot layout 4,4 margins 0.04,0.93,0.05,0.93 spacing 0.05,0.08 \
    title "Reconstructions (lat-long maps; cone rows: visibility, 1 = occluded; mid-range row: radiance)"
set palette defined (-0.3 "#2166ac", 0 "white", 1 "#b2182b")
set cbrange [-0.3:1.1]
set cbtics 0.5 font ",8"
ks = "0.75 1.3 2"
do for [row=0:2] {
  do for [q=0:2] {
    if (row == 0 && q == 0) { set colorbox user origin screen 0.76, screen 0.32 size screen 0.012, screen 0.58; set cblabel "visibility" font ",9" } else { unset colorbox }
    pre = word("cone_exact cone_scaled cone_linear", row+1)
    set title (row == 0 ? "cone occluder, exact" : row == 1 ? "cone-family scaling, order 8" : "linear-family scaling, order 8").", k = ".word(ks,q+1)
    plot outdir.sprintf('/img_%s_%d.dat', pre, q) matrix @ll
  }
  set multiplot next
}
set palette defined (0 "black", 0.5 "#d95f02", 1 "#ffff99")
set cbrange [0:1.6]
set cblabel "radiance" font ",9"
set colorbox user origin screen 0.945, screen 0.06 size screen 0.012, screen 0.14
set title "mid-range k = 0.7, exact"
plot outdir.'/img_mid_exact.dat' matrix @ll
unset colorbox
set title "exact, order-8 projection"
plot outdir.'/img_mid_exact_proj.dat' matrix @ll
set title "plain scaling of the centre capture"
plot outdir.'/img_mid_plain.dat' matrix @ll
set title "energy-preserving scaling"
plot outdir.'/img_mid_energy.dat' matrix @ll
unset multiplot

set output outdir.'/scale_scenes_tilted_images.png'
set terminal pngcairo size 1300,260 enhanced font ",9"
set multiplot layout 1,4 margins 0.04,0.93,0.17,0.82 spacing 0.05,0 \
    title "mid-range k = 0.7 along (θ,φ) = (60°,135°), order 8 (lat-long maps of the radiance)"
set colorbox user origin screen 0.945, screen 0.2 size screen 0.012, screen 0.6
set title "exact"
plot outdir.'/img_tilt_exact.dat' matrix @ll
unset colorbox
set title "exact, order-8 projection"
plot outdir.'/img_tilt_exact_proj.dat' matrix @ll
set title "plain: rotate, scale, rotate back"
plot outdir.'/img_tilt_plain.dat' matrix @ll
set title "energy-preserving"
plot outdir.'/img_tilt_energy.dat' matrix @ll
unset multiplot
