# relative L2 error after bands 0..n-1 of each probe (kept part probes/)
load 'experiments/common/style.gp'
set terminal pngcairo size 1350,540 enhanced font ",11"
f = outdir.'/probe_band_energy.dat'
names = system("grep -v '^#' ".outdir."/probe_names.txt 2>/dev/null | sed 's/.exr$//' | tr '\\n' ' '")
N = words(names)
# one probe per style of style.gp's cycle (colour, point and, from the 8th,
# dash); the points at roughly even steps of log n, so that they do not bunch
mk(n) = (n == 1 || n == 2 || n == 3 || n == 5 || n == 8 || n == 13 || n == 20 || n == 32 || n == 50 || \
         n == 80 || n == 128 || n == 200 || n == 320 || n == 500)
if (N > 0) {
  set output outdir.'/probe_bands.png'
  set multiplot layout 1,2 margins 0.07,0.85,0.13,0.86 spacing 0.08 \
      title "Relative L2 error of the luminance after bands 0..n−1, eight HDR probes"
  set xlabel "order n (bands 0..n−1; log scale)"
  unset key
  set title "radiance"
  set ylabel "relative L2 error of the radiance"
  eval logx(1, 512)
  eval logy(5e-4, 1.5)
  eval budgetl(91, 0.01, "1 %")
  eval budgetl(92, 0.001, "0.1 %")
  plot for [i=0:N-1] f index i using ($1+1):($3>0?$3:1e-9) with lines lt (i+1) lw 1.8 notitle, \
       for [i=0:N-1] f index i using ($1+1):(mk($1+1) && $3 > 0 ? $3 : 1/0) with points lt (i+1) ps 0.8 notitle
  set title "irradiance (convolved with the clamped cosine)"
  set ylabel "relative L2 error of the irradiance"
  eval logx(1, 64)
  eval logy(5e-6, 1.5)
  set key at screen 0.86, screen 0.86 left top Left reverse samplen 3 spacing 1.2 noenhanced title "probe"
  plot for [i=0:N-1] f index i using ($1+1):($4>0?$4:1e-9) with lines lt (i+1) lw 1.8 notitle, \
       for [i=0:N-1] f index i using ($1+1):(mk($1+1) && $4 > 0 ? $4 : 1/0) with points lt (i+1) ps 0.8 notitle, \
       for [i=0:N-1] NaN with linespoints lt (i+1) lw 1.8 ps 0.8 title word(names, i+1)
  unset multiplot
}
