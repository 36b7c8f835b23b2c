# scale_scenes.gp — the occluder and mid-range scenes (style: common/style.gp)
load 'experiments/common/style.gp'
set terminal pngcairo size 1400,800 enhanced font ",10"
set xlabel "k = d / r (log scale)"
set ylabel "relative L2 error |M S_r − E| / |E|"

# One style per (family, preservation); the geometry alone (scaling the exact
# function, no truncation) dashed in the same colour.  The energy-preserving
# curves of the two families nearly coincide: different points keep them apart.
do for [sc in "sphere cone"] {
  set output outdir.'/scale_scenes_'.sc.'.png'
  f = outdir.'/'.sc.'.dat'
  set multiplot layout 2,2 margins 0.06,0.74,0.08,0.9 spacing 0.07,0.11 \
      title (sc eq "sphere" ? "Sphere occluder ρ = r/2: its occlusion captured at d = r, scaled to d = k r (k: the receiver's distance over the capture distance)" : \
             "Cone occluder θ_0 = 45°, non-zonal rim: captured at d = r, scaled to d = k r (k: the receiver's distance over the capture distance)") font ",11"
  set logscale x
  set autoscale xfix
  set xtics (0.5, 0.7, 1, 1.4, 2, 2.5)
  set format x "%g"
  # the sphere's errors stay above 1e-6; the cone family's plain geometry is
  # exact for the cone occluder (~1e-16): said on the panel, not drawn
  # thirteen decades below the rest
  if (sc eq "sphere") { eval logy(1e-6, 10) } else { eval logy(1e-3, 20) }
  conegeom = real(system("awk '!/^#/ && NF && $3 == 1 && $4 == 0 && $6 > m { m = $6 } END { print m + 0 }' ".f))
  if (sc eq "cone") {
      set label 8 sprintf("geometry alone, cone family, plain: ≤ %.0e (exact:\nthe rim lies on the cone), below this axis", conegeom) \
          at graph 0.03, graph 0.08 left font ",8" tc rgb ccol(3) front boxed
  }
  unset key
  do for [o=0:3] {
    set title sprintf("order %d", 2+2*o)
    if (o == 3) {
        set key at screen 0.755, screen 0.9 left top Left reverse samplen 3.5 spacing 1.2 font ",10"
        set label 7 "The energy-preserving curves of the two\nfamilies nearly coincide, and so do their\ntotal and their geometry alone." \
            at screen 0.76, screen 0.55 left font ",9" tc rgb "#333333"
    }
    plot f index o using 1:(($3==0&&$4==0)?$5:1/0) with linespoints lt 1 dt 1 lw 1.8 ps 0.6 title "linear family, plain", \
         f index o using 1:(($3==0&&$4==1)?$5:1/0) with linespoints lt 2 dt 1 lw 1.8 ps 0.9 title "linear family, energy-preserving", \
         f index o using 1:(($3==1&&$4==0)?$5:1/0) with linespoints lt 3 dt 1 lw 1.8 ps 0.6 title "cone family, plain", \
         f index o using 1:(($3==1&&$4==1)?$5:1/0) with linespoints lt 4 dt 1 lw 1.4 ps 0.6 title "cone family, energy-preserving", \
         f index o using 1:(($3==0&&$4==0)?($6>1e-17?$6:1e-17):1/0) with lines lt 1 dt 2 lw 1.4 title "geometry alone: linear, plain", \
         f index o using 1:(($3==1&&$4==0)?($6>1e-17?$6:1e-17):1/0) with lines lt 3 dt 2 lw 1.4 title "geometry alone: cone, plain", \
         f index o using 1:(($3==1&&$4==1)?$6:1/0) with lines lt 4 dt 2 lw 1.4 title "geometry alone: cone, energy"
    unset key
  }
  unset multiplot
  unset label 7
  unset label 8
  unset logscale x
  set xtics autofreq
}

do for [sc in "midrange midrange_tilted"] {
  load 'experiments/scale_scenes/midrange.gpi'
}

# Reconstructions as lat-long images (96×48 samples at pixel centres):
unset ytics; set ytics autofreq; unset mytics
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
