# the probe scene (kept part probes/)
set logscale y
set format y "10^{%T}"
set grid
set key bottom right font ",8"
set xlabel "k"
set ylabel "relative L2 error"
sc = "probe"
load 'experiments/scale_scenes/midrange.gpi'
