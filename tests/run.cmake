# The runner (run/).  Reference cache: keys and files, then two dmbench runs
# (needs GL via dmbench).
dm_add_gl(test_run_refcache test_run_refcache.c LIBS dm_run)
# Quality along a path (run/mpath_quality.c): K's rule and who asks for it.
dm_add_unit(test_run_mpath_quality test_run_mpath_quality.c LIBS dm_run)
add_dependencies(test_run_refcache dmbench)
# The measuring decisions (run/protocol.c), pure: synthetic sample streams.
dm_add_unit(test_run_protocol test_run_protocol.c LIBS dm_protocol)
dm_add_unit(test_run_precision test_run_precision.c LIBS dm_protocol)
# The Instructions pass's pure parts (run/callgrind.c): dump parsing and
# the run's warning when a configuration's samples disagree.
dm_add_unit(test_run_callgrind test_run_callgrind.c LIBS dm_run)
# The user's map and mesh files held to one version a run (run/inputs.c):
# collected once, touched passes, edited or removed named, --resume.
dm_add_unit(test_run_inputs test_run_inputs.c LIBS dm_run)
# TessWalkCalls (run/mscene.c): a two-call frame's per-call counts, taken
# through the renderer's call hook with raw queries, add up to the frame's
# own, and the figure predict counts is their sum by hand.
dm_add_gl(test_run_tess_calls test_run_tess_calls.c LIBS dm_run)
