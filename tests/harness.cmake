dm_add_unit(test_harness_sweep test_harness_sweep.c LIBS dm_plan)
dm_add_unit(test_harness_plan test_harness_plan.c LIBS dm_plan)
# Reference cache: keys and files, then two dmbench runs (needs GL via dmbench).
dm_add_gl(test_harness_refcache test_harness_refcache.c LIBS dm_harness)
add_dependencies(test_harness_refcache dmbench)
