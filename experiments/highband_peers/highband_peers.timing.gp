# ratios shlab / peer against lmax (timing part), with the goals
load 'experiments/common/style.gp'
if (system("test -f ".outdir."/healpix.dat && test -f ".outdir."/sharp.dat && echo y") ne "y") exit
set terminal pngcairo size 1500,580 enhanced font ",11"
set output outdir.'/highband_peers_ratios.png'
h = outdir.'/healpix.dat'
s = outdir.'/sharp.dat'
# the NOISY stamp of a panel: from noise.dat, the load while that panel's peer program ran
noisy(prog) = system(sprintf("awk '!/^#/ && $1 == \"%s\" && $4 == 1 { printf \"NOISY: machine loaded (%%s CPUs)\\nno verdict from these ratios\", $3 }' %s", prog, outdir.'/noise.dat'))
set multiplot layout 1,2 margins 0.07,0.97,0.28,0.88 spacing 0.08 \
    title "Time ratio shlab / peer per repetition, interleaved in one process, one thread (median; bars: quartiles)"
eval stamp(noisy("peer_healpix_bench"))
set logscale xy
set xlabel "lmax (bands 0..lmax)"
set ylabel "shlab time / peer time (ratio)"
set key outside below center vertical maxrows 3 Left reverse samplen 2.5 spacing 1.1 font ",10"
set title "all-band rotation vs HEALPix C++ rotate\\_alm"
set xrange [80:1250]
set xtics (100, 300, 1000)
set yrange [0.01:5]
set ytics (0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5)
set arrow 1 from 80, 0.05 to 1250, 0.05 nohead dt 2 lw 1.5 lc rgb ccol(4)
set arrow 2 from 80, 0.1 to 1250, 0.1 nohead dt 2 lw 1.5 lc rgb ccol(1)
set arrow 3 from 80, 1 to 1250, 1 nohead lw 1 lc rgb "#888888"
set label 1 "goal one-shot ≤ 0.05 (lmax 1000)" at 1200, 0.05*1.12 right tc rgb ccol(4) font ",9"
set label 2 "goal kept ≤ 0.1 (lmax 1000)" at 1200, 0.1*1.12 right tc rgb ccol(1) font ",9"
set label 3 "same time" at 1150, 1.1 right tc rgb "#666666" font ",9"
plot h index 0 using ($1*0.97):3:4:5 with yerrorlines lw 1.8 pt 7 lc rgb ccol(4) title "one-shot (create + apply + free)", \
     h index 1 using 1:3:4:5 with yerrorlines lw 1.8 pt 5 lc rgb ccol(1) title "stream kept, one rotation", \
     h index 2 using ($1*1.03):3:4:5 with yerrorlines lw 1.8 pt 9 lc rgb ccol(3) title "batch of 8, per rotation"
unset arrow; unset label 1; unset label 2; unset label 3
eval stamp(noisy("shlab_bench_peers"))
set title "transforms vs libsharp (thread CPU clock)"
set xrange [200:1300]
set xtics (255, 511, 1023)
set yrange [0.25:4]
set ytics (0.25, 0.5, 1, 2, 4)
set arrow 1 from 450, 0.9 to 1300, 0.9 nohead dt 2 lw 1.5 lc rgb "#C00000"
set arrow 3 from 200, 1 to 1300, 1 nohead lw 1 lc rgb "#888888"
set label 1 "goal ≤ 0.9 (Gauss, lmax 511, 1023)" at 1250, 0.9*0.9 right tc rgb "#C00000" font ",9"
set label 3 "same time" at 1250, 1.06 right tc rgb "#666666" font ",9"
plot s index 0 using ($1*0.985):5:6:7 with yerrorlines lw 1.8 pt 7 lc rgb ccol(2) title "Gauss grid, 1 map: analysis (map2alm)", \
     s index 1 using ($1*0.995):5:6:7 with yerrorlines lw 1.8 pt 5 dt 2 lc rgb ccol(2) title "Gauss grid, 1 map: synthesis (alm2map)", \
     s index 2 using ($1*1.005):5:6:7 with yerrorlines lw 1.8 pt 9 lc rgb ccol(6) title "lat-long 1024×512, 3 channels: analysis", \
     s index 3 using ($1*1.015):5:6:7 with yerrorlines lw 1.8 pt 11 dt 2 lc rgb ccol(6) title "lat-long 1024×512, 3 channels: synthesis"
unset multiplot
