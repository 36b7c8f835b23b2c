# the full study (reports/scene_cache/full, SCENES=full): the same plots
load 'experiments/scene_cache/scene_cache.gp'
