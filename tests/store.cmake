# Results store (store/): round trip, resume, copy, and fault injection
# (killed child, full disk, failing allocations, unopenable paths).
dm_add_unit(test_store test_store.c LIBS dm_store TIMEOUT 120)
# Merge rules (store/merge.c): shards once each, keys once, missing and
# incomplete shards, machines kept apart.
dm_add_unit(test_store_merge test_store_merge.c LIBS dm_store TIMEOUT 30)
