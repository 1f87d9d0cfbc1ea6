# Short fuzz runs of the parsers (libFuzzer, clang), 60 s each, two at a time (6 targets: ~3 min).
add_test(NAME test_fuzz_parsers COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/run.sh)
set_tests_properties(test_fuzz_parsers PROPERTIES TIMEOUT 600 ENVIRONMENT "${DM_TEST_ENV}"
  LABELS "fuzz" RUN_SERIAL TRUE)
