dm_add_unit(test_harness_sweep test_harness_sweep.c LIBS dm_plan)
dm_add_unit(test_harness_plan test_harness_plan.c LIBS dm_plan)
