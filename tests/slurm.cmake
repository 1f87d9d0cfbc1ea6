# dmbench slurm on a real single-node Slurm cluster started by the test
# (munged + slurmctld + slurmd in a temporary directory); skipped (77) only
# where Slurm or MUNGE is not installed.
add_test(NAME test_slurm_array COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/slurm/slurm_array.sh)
set_tests_properties(test_slurm_array PROPERTIES TIMEOUT 300 SKIP_RETURN_CODE 77
  ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;slurm")
dm_reads_resume_full(test_slurm_array)   # the plan's keys (tests/e2e.cmake)
# merge/shard rules end to end without a scheduler: two machines kept apart
# (report, compare), duplicate and missing shards, non-run directories,
# --resume of another shard.
add_test(NAME test_merge_machines COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/slurm/machines.sh)
set_tests_properties(test_merge_machines PROPERTIES TIMEOUT 300 ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;slurm")
dm_reads_resume_full(test_merge_machines)   # the one-machine run (tests/e2e.cmake)
