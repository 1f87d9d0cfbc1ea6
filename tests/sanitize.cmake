# ASan + UBSan build of the unit and GL integration tests (tests/sanitize.sh),
# unless this build is itself the sanitizer build: one test builds the tree
# (build/asan, reused by the next run) and seven run its tests in shares that
# ctest can run side by side, each one well under 120 s on two cores.  The
# shares: the store's unit tests (test_store's allocation-fault loops are
# the longest unit test), the models' unit tests (their simulations), the
# other unit tests, the quality truth
# (test_techniques_quality), test_techniques_geometry_gl, the
# other GL tests of the techniques layer, the other GL tests; each selects
# by name and the next excludes it, so together they run every unit and GL
# test that is not `slow`, each once.
if(NOT DM_SANITIZE)
  set(san_env "DMBENCH_SOURCE_DIR=${CMAKE_SOURCE_DIR}" "SANITIZE_BUILD=${CMAKE_BINARY_DIR}/asan"
      "SANITIZE_LAUNCHER=${CMAKE_C_COMPILER_LAUNCHER}")
  add_test(NAME test_sanitize_build COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/sanitize.sh build)
  set_tests_properties(test_sanitize_build PROPERTIES TIMEOUT 1500 LABELS "sanitize"
    ENVIRONMENT "${san_env}" FIXTURES_SETUP dm_asan_tree)
  function(dm_sanitize_share share)
    add_test(NAME test_sanitize_${share} COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/sanitize.sh run ${ARGN})
    set_tests_properties(test_sanitize_${share} PROPERTIES TIMEOUT 900 LABELS "sanitize"
      ENVIRONMENT "${san_env}" FIXTURES_REQUIRED dm_asan_tree)
  endfunction()
  dm_sanitize_share(unit_store -L ^unit$ -R ^test_store)
  dm_sanitize_share(unit_models -L ^unit$ -R ^test_models_)
  dm_sanitize_share(unit -L ^unit$ -E "^test_(store|models_)")
  dm_sanitize_share(gl_quality -L ^gl$ -R ^test_techniques_quality$)
  dm_sanitize_share(gl_geometry -L ^gl$ -R ^test_techniques_geometry_gl$)
  dm_sanitize_share(gl_techniques -L ^gl$ -R ^test_techniques_ -E "^test_techniques_(quality|geometry_gl)$")
  dm_sanitize_share(gl_other -L ^gl$ -E ^test_techniques_)
endif()
