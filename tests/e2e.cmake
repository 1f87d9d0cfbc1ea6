# End-to-end CLI tests: the real binary on llvmpipe, a tiny sweep, bad input.
function(dm_add_e2e name script)
  add_test(NAME ${name} COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/e2e/${script})
  set_tests_properties(${name} PROPERTIES TIMEOUT 600 ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e")
endfunction()
dm_add_e2e(test_e2e_run_tiny run_tiny.sh)
dm_add_e2e(test_e2e_bad_input bad_input.sh)
dm_add_e2e(test_e2e_unavailable unavailable.sh)
dm_add_e2e(test_e2e_resume resume.sh)
dm_add_e2e(test_e2e_watchdog watchdog.sh)
# The project's own regression gate: the deterministic counters of
# ci/gate.yaml must equal ci/baseline.json (no timing, so no noise), and
# its Instructions (one Valgrind child: ~1 min quiet, more under load) too.
# The project's CI gate (ci/gate.sh) passes: its run is made once for the
# suite by test_ci_gate_run (fixture ci_gate_run, tests/instructions.cmake),
# which test_instructions_gate and test_instructions_uber read too.
add_test(NAME test_ci_gate COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/ci_gate.sh
  ${CMAKE_BINARY_DIR}/test-runs/ci-gate)
set_tests_properties(test_ci_gate PROPERTIES TIMEOUT 120 FIXTURES_REQUIRED ci_gate_run
  ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;gate")
dm_add_e2e(test_e2e_quick quick.sh)
dm_add_e2e(test_e2e_exchange exchange.sh)
dm_add_e2e(test_e2e_faults faults.sh)
dm_add_e2e(test_e2e_hostile hostile.sh)
dm_add_e2e(test_e2e_dry_run dry_run.sh)
dm_add_e2e(test_e2e_user_mesh user_mesh.sh)
dm_add_e2e(test_e2e_published published.sh)
dm_add_e2e(test_e2e_study_sweeps study_sweeps.sh)
dm_add_e2e(test_e2e_vt_quality vt_quality.sh)
dm_add_e2e(test_e2e_drivers drivers.sh)
set_tests_properties(test_e2e_drivers PROPERTIES SKIP_RETURN_CODE 77)
# The hostile corpus: >= 100 cases over every command, each with its exit
# code and first words, and the conditions table of docs/reliability.md
# checked row by row (about 2-3 min on 2 cores; nothing renders above 16x16).
dm_add_e2e(test_e2e_corpus corpus.sh)
# docs/ci-gating.md's recipe, run as written (ci/perf-gate.sh, baselines).
# docs/ci-gating.md's recipe as written, in two parts side by side: the
# job (ci/perf-gate.sh) and the baseline recipe (its dmbench lines).
add_test(NAME test_ci_recipe COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/e2e/ci_recipe.sh perf-gate)
set_tests_properties(test_ci_recipe PROPERTIES TIMEOUT 1800 ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;gate")
add_test(NAME test_ci_recipe_baseline COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/e2e/ci_recipe.sh baseline)
set_tests_properties(test_ci_recipe_baseline PROPERTIES TIMEOUT 1800 ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;gate")
# User techniques (docs/user-techniques.md): the contract without Valgrind
# (axes, keys, bit-exact normal, every bad file, watchdog, NaN; ~30 s) and
# the instruction gate on them (tests/user_technique/gate.sh).
add_test(NAME test_user_technique_contract COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/user_technique/contract.sh)
set_tests_properties(test_user_technique_contract PROPERTIES TIMEOUT 600 ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e")
add_test(NAME test_user_technique_gate COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/user_technique/gate.sh)
set_tests_properties(test_user_technique_gate PROPERTIES TIMEOUT 1800 ENVIRONMENT "${DM_TEST_ENV}"
  LABELS "e2e;gate;valgrind")
# No process outlives its run: SIGTERM and SIGKILL of the parent at each
# stage with a child (probe, measuring, Valgrind counting, drivers' run)
# leave nothing running 5 s later (~1 min).
dm_add_e2e(test_e2e_kill kill.sh)
