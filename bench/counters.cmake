# Cost of measuring with counters/ (docs/measurement.md, Performance targets); run by hand, not a test.
add_executable(bench_counters_overhead ${CMAKE_CURRENT_LIST_DIR}/counters_overhead.c)
target_link_libraries(bench_counters_overhead PRIVATE dm_counters dm_glctx dm_core)
