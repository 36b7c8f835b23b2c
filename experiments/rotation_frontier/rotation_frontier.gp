# error against counted multiplications per rotation (deterministic)
load 'experiments/common/style.gp'
f = outdir.'/frontier.dat'
names = system("sed -n '5,$p' ".outdir."/methods.txt | tr '\\n' ' '")
noisy = ""
do for [meas in "lobe max"] {
    xcol = 4
    ycol = (meas eq "lobe") ? 7 : 8
    xlab = "multiplications per rotation (counted, set + apply)"
    ylab = (meas eq "lobe") ? "lobe error ‖Dc‖ (unit lobe)" : "max error σ_{max}(D)"
    xlo = 50; xhi = 3e5
    tlo = (meas eq "lobe") ? 1e-4 : 1e-3
    thi = (meas eq "lobe") ? 10 : 100
    out = outdir.'/rotation_frontier_'.meas.'.png'
    ttl = (meas eq "lobe" ? "Lobe error" : "Max error")." against cost; each curve joins orders n = 4 … 12 " . \
          "(end points labelled with n); errors below 10^{-17} drawn at 10^{-17}"
    load 'experiments/rotation_frontier/frontier.gpi'
}
