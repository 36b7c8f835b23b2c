# scene_cache.gp (also the full part: scene_cache.full.gp loads it)
load 'experiments/common/style.gp'

# cache_a.png: the cache's errors against the allowed error a, one panel per
# scene × order, one legend.  Interpolation and "ignore" can coincide (Wuson:
# the unrotated records are about as good as the rotated ones there): ignore
# is drawn first, wide and light with large open markers, interpolation on top
# thin with small filled ones, so both stay visible.
f = outdir.'/cache_a.dat'
scenes = system("grep -v '^#' ".outdir."/cache_noise.dat | awk '{print $1}' | tr '\\n' ' '")
NS = words(scenes)
HPX = 130 + 400 * NS
set terminal pngcairo size 1350, HPX enhanced font ",11"
set output outdir.'/cache_a.png'
TOP = 1 - 75.0 / HPX
set multiplot layout NS,2 margins 0.07,0.74,60.0 / HPX,TOP spacing 0.07,90.0 / HPX \
    title "Radiance cache: relative L2 error of the luminance over every vertex against the allowed error a" font ",11"
eval logy(1e-6, 1)
eval logx(0.04, 0.6)
set xtics ("0.05" 0.05, "0.1" 0.1, "0.2" 0.2, "0.3" 0.3, "0.5" 0.5)
set xlabel "allowed error a of the cache (weight threshold)"
set ylabel "relative L2 error of the luminance"
unset key
do for [s=1:NS] {
  sc = word(scenes, s)
  noise = real(system("grep -v '^#' ".outdir."/cache_noise.dat | awk '$1 == \"".sc."\" {print $2}'"))
  do for [o in "6 10"] {
    set title sc." — order ".o noenhanced
    if (s == 1 && o eq "10") {
        set key at screen 0.755, screen TOP left top Left reverse samplen 3 spacing 1.25 font ",10"
        set label 7 "Where the black line runs inside the wide grey one,\nleaving the records unrotated costs nothing:\nthe cache's error is not the rotation's." \
            at screen 0.76, screen TOP - 150.0 / HPX left font ",9" tc rgb "#333333"
    }
    plot f using 3:((strcol(1) eq sc && $2 == int(o)) ? $10 : 1/0) with linespoints lw 5 ps 2.2 pt 6 lc rgb "#B8B8B8" dt 1 \
            title "no rotation (ignore) vs direct", \
         f using 3:((strcol(1) eq sc && $2 == int(o)) ? $8 : 1/0) with linespoints lw 1.6 ps 0.8 pt 7 lc rgb "#000000" dt 1 \
            title "interpolation (exact rotation) vs direct", \
         f using 3:((strcol(1) eq sc && $2 == int(o)) ? $11 : 1/0) with linespoints lw 1.6 ps 0.8 \
            lc rgb mcol("taylor1") pt mpt("taylor1") dt mdt("taylor1") title "taylor1 vs exact rotation", \
         f using 3:((strcol(1) eq sc && $2 == int(o)) ? $12 : 1/0) with linespoints lw 1.6 ps 0.8 \
            lc rgb mcol("zxzxz") pt mpt("taylor1.5") dt mdt("taylor1.5") title "taylor1.5 vs exact rotation", \
         f using 3:((strcol(1) eq sc && $2 == int(o)) ? $13 : 1/0) with linespoints lw 1.6 ps 0.8 \
            lc rgb mcol("taylor2") pt mpt("taylor2") dt mdt("taylor2") title "taylor2 vs exact rotation", \
         noise with lines dt 3 lw 1.6 lc rgb "#555555" title "direct computation's noise (order 6)"
    unset key
    unset label 7
  }
}
unset multiplot

# the pictures with their colour bars (sh_image_colormap)
mapsfx = "_error"
errlabel = "|cache − every vertex directly| / RMS"
errmax = 0.1
load 'experiments/common/errormap.gpi'
mapsfx = "_phong_rotdiff"
errlabel = "|taylor1.5 − zxzxz|, display scale [0, 1]"
errmax = 0.02
load 'experiments/common/errormap.gpi'
