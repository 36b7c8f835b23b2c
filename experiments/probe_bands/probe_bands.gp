set terminal pngcairo size 1300,560 enhanced font ",11"
f = outdir.'/probe_band_energy.dat'
names = system("grep -v '^#' ".outdir."/probe_names.txt 2>/dev/null | sed 's/.exr$//' | tr '\\n' ' '")
N = words(names)
set logscale xy
set format y "10^{%T}"
set xlabel "order n (bands 0..n-1)"
set ylabel "relative L2 error of luminance"
set grid
set key outside right noenhanced
set arrow from graph 0, first 0.01 to graph 1, first 0.01 nohead dt 2
set arrow from graph 0, first 0.001 to graph 1, first 0.001 nohead dt 2
if (N > 0) {
  set output outdir.'/probe_bands.png'
  set multiplot layout 1,2
  set title "radiance"
  plot for [i=0:N-1] f index i using ($1+1):($3>0?$3:1e-9) with lines lw 1.5 title word(names, i+1)
  set title "irradiance (clamped-cosine convolution)"
  set ylabel "relative L2 error of irradiance"
  set xrange [1:64]
  plot for [i=0:N-1] f index i using ($1+1):($4>0?$4:1e-9) with lines lw 1.5 title word(names, i+1)
  unset multiplot
}
# no probes: probe_bands.c already wrote the "skipped" paragraph; draw nothing
