dm_add_unit(test_core test_core.c)
