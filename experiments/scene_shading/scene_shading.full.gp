# the full study (reports/scene_shading/full, SCENES=full): the same plots
load 'experiments/scene_shading/scene_shading.gp'
