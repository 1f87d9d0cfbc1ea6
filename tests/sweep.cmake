# Sweep files and the planner (sweep/): parsing, validation and planning.
dm_add_unit(test_sweep_parse test_sweep_parse.c LIBS dm_plan)
dm_add_unit(test_sweep_plan test_sweep_plan.c LIBS dm_plan)
dm_add_unit(test_sweep_published test_sweep_published.c LIBS dm_plan)
dm_add_unit(test_sweep_fraction test_sweep_fraction.c LIBS dm_plan)
