# Planning time of large sweep files (linear in the combinations); by hand.
add_executable(bench_plan_scale ${CMAKE_CURRENT_LIST_DIR}/plan_scale.c)
target_link_libraries(bench_plan_scale PRIVATE dm_plan dm_core m)
