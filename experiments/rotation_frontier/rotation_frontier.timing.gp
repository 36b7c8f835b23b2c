# lobe error against time per rotation (timing part)
load 'experiments/common/style.gp'
f = outdir.'/frontier_time.dat'
names = system("sed -n '5,$p' ".outdir."/../methods.txt | tr '\\n' ' '")
# the orders whose interleaved run broke the noise criterion (column 12), from the data
nord = system("awk '!/^#/ && NF && $12 == 1 { o[$3] = 1 } END { for (k in o) print k }' ".outdir."/frontier_time.dat | sort -n | tr '\\n' ' '")
noisy = words(nord) > 0 ? "NOISY: the runs of orders ".nord."broke the noise criterion" : ""
xcol = 4
ycol = 10
xlab = "ns per rotation (3×3 matrix → set → apply; median)"
ylab = "lobe error ‖Dc‖ (unit lobe)"
xlo = 50; xhi = 2e5
tlo = 1e-4; thi = 10
out = outdir.'/rotation_frontier_lobe_time.png'
ttl = "Lobe error against time per rotation (one interleaved run per order); each curve joins orders n = 4 … 12 " . \
      "(end points labelled with n)"
load 'experiments/rotation_frontier/frontier.gpi'
