# Harness overhead against a raw-GL loop (docs/measurement.md, Performance targets); run by hand, not a test.
add_executable(bench_overhead ${CMAKE_CURRENT_LIST_DIR}/overhead.c)
target_link_libraries(bench_overhead PRIVATE dm_run dm_techniques dm_counters dm_models dm_glctx dm_core PkgConfig::CJSON m)
target_compile_definitions(bench_overhead PRIVATE DM_DMBENCH_PATH="$<TARGET_FILE:dmbench>")
add_dependencies(bench_overhead dmbench)
