# End-to-end CLI tests: the real binary on llvmpipe, a tiny sweep, bad input.
# dm_add_e2e(name script [ARGS ...] [LABELS ...]): `quick` among the labels
# puts it in the quick tier (tests/CMakeLists.txt).
function(dm_add_e2e name script)
  cmake_parse_arguments(A "" "" "ARGS;LABELS" ${ARGN})
  add_test(NAME ${name} COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/e2e/${script} ${A_ARGS})
  set_tests_properties(${name} PROPERTIES TIMEOUT 600 ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;${A_LABELS}")
endfunction()
dm_add_e2e(test_e2e_run_tiny run_tiny.sh LABELS quick)
dm_add_e2e(test_e2e_bad_input bad_input.sh LABELS quick)
dm_add_e2e(test_e2e_unavailable unavailable.sh)
# Camera paths drawn frame by frame against still renders (docs/motion.md).
dm_add_e2e(test_e2e_paths paths.sh LABELS quick)
dm_add_e2e(test_e2e_motion_ladder motion_ladder.sh)
# An uninterrupted run of tests/e2e/resume.yaml made once (fixture
# resume_full, build/test-runs/resume-full) for the three tests that each
# made it before: test_e2e_resume, test_merge_machines (tests/slurm.cmake)
# and test_slurm_array read it through RESUME_FULL (tests/e2e/resume_full.sh).
set(DM_RESUME_FULL ${CMAKE_BINARY_DIR}/test-runs/resume-full)
dm_add_e2e(test_e2e_resume_full resume_full.sh ARGS ${DM_RESUME_FULL})
set_tests_properties(test_e2e_resume_full PROPERTIES FIXTURES_SETUP resume_full)
dm_add_e2e(test_e2e_resume resume.sh)
dm_add_e2e(test_e2e_watchdog watchdog.sh LABELS quick)
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
# Three runs of the embedded --quick sweep made once (fixture quick_runs,
# DM_QUICK_RUNS, tests/e2e/quick_runs.sh) for the three tests that
# made six between them before: test_e2e_quick, test_e2e_precision and
# test_reports_quick_browser (tests/reports.cmake) read them.
dm_add_e2e(test_e2e_quick_runs quick_runs.sh ARGS ${DM_QUICK_RUNS} LABELS quick)
set_tests_properties(test_e2e_quick_runs PROPERTIES FIXTURES_SETUP quick_runs)
dm_add_e2e(test_e2e_quick quick.sh LABELS quick)
dm_add_e2e(test_e2e_precision precision.sh)
foreach(t test_e2e_quick test_e2e_precision)
  set_tests_properties(${t} PROPERTIES FIXTURES_REQUIRED quick_runs)
  set_property(TEST ${t} APPEND PROPERTY ENVIRONMENT "QUICK_RUNS=${DM_QUICK_RUNS}")
endforeach()
dm_add_e2e(test_e2e_extra_rounds extra_rounds.sh)
dm_add_e2e(test_e2e_precision_raw precision_raw.sh)
dm_add_e2e(test_e2e_exchange exchange.sh)
dm_add_e2e(test_e2e_faults faults.sh)
dm_add_e2e(test_e2e_hostile hostile.sh)
dm_add_e2e(test_e2e_dry_run dry_run.sh LABELS quick)
dm_add_e2e(test_e2e_user_mesh user_mesh.sh)
dm_add_e2e(test_e2e_published published.sh)
dm_add_e2e(test_e2e_study_sweeps study_sweeps.sh)
dm_add_e2e(test_e2e_vt_quality vt_quality.sh)
dm_add_e2e(test_e2e_drivers drivers.sh)
set_tests_properties(test_e2e_drivers PROPERTIES SKIP_RETURN_CODE 77)
# The hostile corpus (tests/e2e/corpus.sh): >= 100 cases over every
# command, each with its exit code and first words; nothing renders above
# 16x16.  It runs in seven shares by case class, side by side, each writing
# the cases it ran to build/corpus-ran/; the last share takes every class
# the others do not name.  test_e2e_corpus_table then checks the conditions
# table of docs/reliability.md row by row against all of them (the shares
# are its fixture: ctest -R test_e2e_corpus_table runs them first).
set(corpus_shares
  sweep    "sweep/"                           # refused at parse time: in the quick tier
  input    "map/ mesh/ results/ csv/"
  store    "store/ cli/ slurm/"
  env      "env/ signal/"
  children "children/ glsl/"
  images   "images/")
# The small real run the cases damage (stores, results), made once for the
# suite (fixture dm_corpus_fixture) and copied by each share that needs it;
# the sweep/ share needs none, so the quick tier runs no fixture.
set(corpus_fixture ${CMAKE_BINARY_DIR}/test-runs/corpus-fixture)
dm_add_e2e(test_e2e_corpus_fixture corpus.sh ARGS fixture ${corpus_fixture})
set_tests_properties(test_e2e_corpus_fixture PROPERTIES FIXTURES_SETUP dm_corpus_fixture)
set(corpus_named "")
set(corpus_files "")
while(corpus_shares)
  list(POP_FRONT corpus_shares share classes)
  string(APPEND corpus_named "${classes} ")
  list(APPEND corpus_files "${CMAKE_BINARY_DIR}/corpus-ran/${share}")
  dm_add_e2e(test_e2e_corpus_${share} corpus.sh ARGS ${share})   # the argument names the share in its output
  set_property(TEST test_e2e_corpus_${share} APPEND PROPERTY ENVIRONMENT
    "CORPUS_CLASSES=${classes}" "CORPUS_RAN=${CMAKE_BINARY_DIR}/corpus-ran/${share}")
  set_tests_properties(test_e2e_corpus_${share} PROPERTIES FIXTURES_SETUP dm_corpus_ran)
  if(share STREQUAL "sweep")
    set_property(TEST test_e2e_corpus_${share} APPEND PROPERTY ENVIRONMENT "CORPUS_FIXTURE=none")
  else()
    set_property(TEST test_e2e_corpus_${share} APPEND PROPERTY ENVIRONMENT "CORPUS_FIXTURE=${corpus_fixture}")
    set_property(TEST test_e2e_corpus_${share} APPEND PROPERTY FIXTURES_REQUIRED dm_corpus_fixture)
  endif()
endwhile()
set_property(TEST test_e2e_corpus_sweep APPEND PROPERTY LABELS quick)
dm_add_e2e(test_e2e_corpus_numbers corpus.sh ARGS numbers)   # gate/ predict/ compare/ drivers/ baseline/ and any new class
list(APPEND corpus_files "${CMAKE_BINARY_DIR}/corpus-ran/numbers")
set_property(TEST test_e2e_corpus_numbers APPEND PROPERTY ENVIRONMENT
  "CORPUS_EXCEPT=${corpus_named}" "CORPUS_RAN=${CMAKE_BINARY_DIR}/corpus-ran/numbers")
set_tests_properties(test_e2e_corpus_numbers PROPERTIES FIXTURES_SETUP dm_corpus_ran
  FIXTURES_REQUIRED dm_corpus_fixture)
set_property(TEST test_e2e_corpus_numbers APPEND PROPERTY ENVIRONMENT "CORPUS_FIXTURE=${corpus_fixture}")
string(REPLACE ";" " " corpus_files "${corpus_files}")
dm_add_e2e(test_e2e_corpus_table corpus.sh ARGS table)
set_property(TEST test_e2e_corpus_table APPEND PROPERTY ENVIRONMENT "CORPUS_TABLE=${corpus_files}")
set_tests_properties(test_e2e_corpus_table PROPERTIES FIXTURES_REQUIRED dm_corpus_ran TIMEOUT 60)
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
dm_add_e2e(test_e2e_counters_only counters_only.sh)

# The readers of the fixture resume_full (above); test_merge_machines and
# test_slurm_array are declared in tests/slurm.cmake, which comes later.
function(dm_reads_resume_full name)
  set_property(TEST ${name} APPEND PROPERTY ENVIRONMENT "RESUME_FULL=${DM_RESUME_FULL}")
  set_property(TEST ${name} APPEND PROPERTY FIXTURES_REQUIRED resume_full)
endfunction()
dm_reads_resume_full(test_e2e_resume)
