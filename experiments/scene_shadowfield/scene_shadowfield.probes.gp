# the probes part (reports/scene_shadowfield/probes): the same plots
load 'experiments/scene_shadowfield/scene_shadowfield.gp'
