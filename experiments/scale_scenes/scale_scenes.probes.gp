# the probe scene (kept part probes/)
load 'experiments/common/style.gp'
sc = "probe"
load 'experiments/scale_scenes/midrange.gpi'
