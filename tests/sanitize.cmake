# ASan + UBSan build of the unit and GL integration tests, unless this build
# is itself the sanitizer build.
if(NOT DM_SANITIZE)
  add_test(NAME test_sanitizers COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/sanitize.sh)
  set_tests_properties(test_sanitizers PROPERTIES TIMEOUT 1500 RUN_SERIAL TRUE LABELS "sanitize"
    ENVIRONMENT "DMBENCH_SOURCE_DIR=${CMAKE_SOURCE_DIR};SANITIZE_BUILD=${CMAKE_BINARY_DIR}/asan")
endif()
