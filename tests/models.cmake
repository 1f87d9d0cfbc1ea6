# models/: statistics, formula language, Ceres fits, regression-gate statistics.
dm_add_unit(test_models_stats test_models_stats.c LIBS dm_models)
dm_add_unit(test_models_formula test_models_formula.c LIBS dm_models)
dm_add_unit(test_models_fit test_models_fit.c LIBS dm_models)
dm_add_unit(test_models_compare test_models_compare.c LIBS dm_models)
dm_add_unit(test_models_data test_models_data.c LIBS dm_models)
dm_add_unit(test_models_changepoint test_models_changepoint.c LIBS dm_models)
# Predictions of stored fits for --budget (run/fitting.c).
dm_add_unit(test_models_predict test_models_predict.c LIBS dm_run)
# The stage-instructions model on synthetic runs with known coefficients.
dm_add_unit(test_models_stage test_models_stage.c LIBS dm_run)
# --budget end to end: the real binary predicts from a stored fit (~10 s).
dm_add_gl(test_models_budget test_models_budget.c LIBS dm_core LABELS e2e)
add_dependencies(test_models_budget dmbench)
dm_add_unit(test_models_blocking test_models_blocking.c LIBS dm_models)
dm_add_unit(test_models_drift test_models_drift.c LIBS dm_models)
# Frame times along a path: percentiles, 1 % lows, stutters (models/frame_series.h).
dm_add_unit(test_models_frame_series test_models_frame_series.c LIBS dm_models)
# fit's name checks end to end (exit 2 with a suggestion).
add_test(NAME test_fit_names COMMAND bash ${CMAKE_SOURCE_DIR}/tests/stages/fit_names.sh)
set_tests_properties(test_fit_names PROPERTIES TIMEOUT 60 ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;quick")
