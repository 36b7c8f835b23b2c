# relative L2 error after bands 0..n-1 of each probe (kept part probes/)
load 'experiments/common/style.gp'
set terminal pngcairo size 1300,520 enhanced font ",11"
f = outdir.'/probe_band_energy.dat'
names = system("grep -v '^#' ".outdir."/probe_names.txt 2>/dev/null | sed 's/.exr$//' | tr '\\n' ' '")
N = words(names)
pcols = "#4E79A7 #F28E2B #E15759 #76B7B2 #59A14F #B07AA1 #9C755F #000000"
pdt(i) = i % 4 + 1
set logscale xy
set format y "10^{%T}"
set xlabel "order n (bands 0..n−1)"
set arrow 1 from graph 0, first 0.01 to graph 1, first 0.01 nohead dt 3 lc rgb "#666666"
set arrow 2 from graph 0, first 0.001 to graph 1, first 0.001 nohead dt 3 lc rgb "#666666"
set label 1 "1 %" at graph 0.01, first 0.012 font ",9" tc rgb "#666666"
set label 2 "0.1 %" at graph 0.01, first 0.0012 font ",9" tc rgb "#666666"
if (N > 0) {
  set output outdir.'/probe_bands.png'
  set multiplot layout 1,2 title "relative L2 error of the luminance after bands 0..n−1, eight HDR probes"
  set title "radiance"
  set ylabel "relative L2 error of radiance"
  set xrange [1:512]
  set yrange [5e-4:1.5]
  unset key
  plot for [i=0:N-1] f index i using ($1+1):($3>0?$3:1e-9) with lines lw 2 dt pdt(i) lc rgb word(pcols, i%8+1) title word(names, i+1)
  set title "irradiance (convolved with the clamped cosine)"
  set ylabel "relative L2 error of irradiance"
  set xrange [1:64]
  set yrange [5e-6:1.5]
  set key outside right top Left reverse noenhanced
  plot for [i=0:N-1] f index i using ($1+1):($4>0?$4:1e-9) with lines lw 2 dt pdt(i) lc rgb word(pcols, i%8+1) title word(names, i+1)
  unset multiplot
}
