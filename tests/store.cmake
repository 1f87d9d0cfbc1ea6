# Results store (store/): round trip, resume, copy, and fault injection
# (killed child, full disk, failing allocations, unopenable paths).
dm_add_unit(test_store test_store.c LIBS dm_store TIMEOUT 120)
