# dmbench slurm on a real single-node Slurm cluster started by the test
# (munged + slurmctld + slurmd in a temporary directory); skipped (77) only
# where Slurm or MUNGE is not installed.
add_test(NAME test_slurm_array COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/slurm/slurm_array.sh)
set_tests_properties(test_slurm_array PROPERTIES TIMEOUT 300 SKIP_RETURN_CODE 77
  ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;slurm" RUN_SERIAL TRUE)
