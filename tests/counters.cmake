# Counters layer tests: registry + formula evaluator (no GL), and GL
# integration on llvmpipe with analytic expected values.
dm_add_unit(test_counters_registry test_counters_registry.c LIBS dm_counters)
dm_add_gl(test_counters_gl test_counters_gl.c LIBS dm_counters)
