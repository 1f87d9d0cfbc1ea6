# The calibration workload's own spread (docs/ci-gating.md); run by hand, not a test.
add_executable(bench_calibrate ${CMAKE_CURRENT_LIST_DIR}/calibrate.c)
target_link_libraries(bench_calibrate PRIVATE dm_run dm_glctx dm_models dm_core m)
