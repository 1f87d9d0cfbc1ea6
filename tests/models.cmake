# models/: statistics, formula language, Ceres fits, regression-gate statistics.
dm_add_unit(test_models_stats test_models_stats.c LIBS dm_models)
dm_add_unit(test_models_formula test_models_formula.c LIBS dm_models)
dm_add_unit(test_models_fit test_models_fit.c LIBS dm_models)
dm_add_unit(test_models_compare test_models_compare.c LIBS dm_models)
dm_add_unit(test_models_data test_models_data.c LIBS dm_models)
