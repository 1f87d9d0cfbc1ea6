# Short fuzz runs of the parsers (libFuzzer, clang; tests/fuzz/run.sh): one
# test builds the targets (build/fuzz, reused by the next run), then each
# target is a test of its own: its stored corpus replayed in full, then
# FUZZ_SECONDS (5 unless set) of new inputs.  One core each, so ctest runs
# them side by side.  Fuzz for longer with FUZZ_SECONDS=600 ctest -L fuzz.
set(fuzz_env ${DM_TEST_ENV} "FUZZ_WORK=${CMAKE_BINARY_DIR}/fuzz"
    "FUZZ_LAUNCHER=${CMAKE_C_COMPILER_LAUNCHER}")
add_test(NAME test_fuzz_build COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/run.sh build)
set_tests_properties(test_fuzz_build PROPERTIES TIMEOUT 900 ENVIRONMENT "${fuzz_env}"
  LABELS "fuzz" FIXTURES_SETUP dm_fuzz_build)
foreach(t sweep formula expr csv results glsl image)
  add_test(NAME test_fuzz_${t} COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/run.sh ${t})
  set_tests_properties(test_fuzz_${t} PROPERTIES TIMEOUT 900 ENVIRONMENT "${fuzz_env}"
    LABELS "fuzz" FIXTURES_REQUIRED dm_fuzz_build)
endforeach()
