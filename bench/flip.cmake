# FLIP on a 1920x1080 pair, one thread; by hand.
add_executable(bench_flip ${CMAKE_CURRENT_LIST_DIR}/flip.c)
target_link_libraries(bench_flip PRIVATE dm_imaging dm_core m)
