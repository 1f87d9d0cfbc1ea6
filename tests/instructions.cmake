# The Instructions pass and the gate on it (run/callgrind.c, gate/): real
# runs under Valgrind callgrind of the CI gate's sweeps and of small sweeps
# of their own.
#
# dmbench_slowshader is dmbench with a test-only copy of the GLSL whose
# surface fragment shader does DM_SLOW_STEPS more steps per fragment
# (tests/instructions/slow_glsl.cmake); its embedded shader table replaces
# the real one at link time (an object given to the linker wins over the
# archive member defining the same table).  No production code path reads
# anything that makes shaders slower.  The tests assume 1; bench/power.sh
# builds it with more in a tree of its own (-DDM_SLOW_STEPS=8).
set(DM_SLOW_STEPS 1 CACHE STRING "extra steps per fragment of dmbench_slowshader (tests: 1)")
file(GLOB DM_GLSL_IN CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/techniques/glsl/*.glsl)

# dm_glsl_variant(NAME SCRIPT [ARGS -D...] [DEPENDS files]): dmbench_NAMEshader,
# dmbench with the GLSL that SCRIPT writes from techniques/glsl/ embedded in
# place of the real table.
function(dm_glsl_variant name script)
  cmake_parse_arguments(V "" "" "ARGS;DEPENDS" ${ARGN})
  set(dir ${CMAKE_CURRENT_BINARY_DIR}/${name}_glsl)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/shaders_${name}.c)
  add_custom_command(OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DGLSL_DIR=${CMAKE_SOURCE_DIR}/techniques/glsl -DOUT_DIR=${dir} ${V_ARGS}
            -P ${script}
    COMMAND ${CMAKE_COMMAND} -DGLSL_DIR=${dir} -DOUT=${out} -P ${CMAKE_SOURCE_DIR}/cmake/embed_glsl.cmake
    DEPENDS ${DM_GLSL_IN} ${script} ${V_DEPENDS} ${CMAKE_SOURCE_DIR}/cmake/embed_glsl.cmake
    COMMENT "Embedding the test-only GLSL of dmbench_${name}shader")
  add_executable(dmbench_${name}shader ${CMAKE_SOURCE_DIR}/cli/main.c ${out})
  target_link_libraries(dmbench_${name}shader PRIVATE dm_cli)
endfunction()

dm_glsl_variant(slow ${CMAKE_CURRENT_SOURCE_DIR}/instructions/slow_glsl.cmake ARGS -DSTEPS=${DM_SLOW_STEPS})
# One slower shader per stage family (instructions/families.sh): the
# vertex stage of vertex-displacement, the evaluation stage of
# tess-displacement.
dm_glsl_variant(slowvertex ${CMAKE_CURRENT_SOURCE_DIR}/instructions/slow_glsl.cmake
  ARGS -DSTEPS=512 -DFAMILY=vertex)
dm_glsl_variant(slowtess ${CMAKE_CURRENT_SOURCE_DIR}/instructions/slow_glsl.cmake
  ARGS -DSTEPS=64 -DFAMILY=tess)

# Counted runs made once and read by several tests (ctest fixtures; the
# runs stay under build/test-runs/).  A reader asked for alone
# (`ctest -R test_instructions_gate`) brings its fixture's run with it.
#   ci_gate_run     ci/gate.sh on both gate sweeps: test_ci_gate (its exit
#                   code), test_instructions_gate (gate.yaml, the first of
#                   its two dmbench runs), test_instructions_uber (dmbench's
#                   side: gate-techniques.yaml's configurations with VT off)
#   stage_run_cube  tests/stages/techniques.yaml: test_stage_instructions,
#                   test_instructions_families (dmbench's side)
#   stage_run_reference  tests/stages/reference.yaml (the cube's
#                   reference-mesh, as long to count as the other nine
#                   techniques together, so in a run of its own beside
#                   theirs): test_stage_instructions
#   stage_run_fullscreen  tests/stages/fullscreen.yaml: test_stage_instructions
set(DM_TEST_RUNS ${CMAKE_BINARY_DIR}/test-runs)
add_test(NAME test_ci_gate_run
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/gate_run.sh ${DM_TEST_RUNS}/ci-gate)
set_tests_properties(test_ci_gate_run PROPERTIES TIMEOUT 1800 FIXTURES_SETUP ci_gate_run
  ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;gate;valgrind")
foreach(part cube reference fullscreen)
  if(part STREQUAL cube)
    set(sweep ${CMAKE_CURRENT_SOURCE_DIR}/stages/techniques.yaml)
  else()
    set(sweep ${CMAKE_CURRENT_SOURCE_DIR}/stages/${part}.yaml)
  endif()
  add_test(NAME test_stage_run_${part}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/fixture_run.sh ${DM_TEST_RUNS}/stages-${part} ${sweep})
  set_tests_properties(test_stage_run_${part} PROPERTIES TIMEOUT 1800 FIXTURES_SETUP stage_run_${part}
    ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;valgrind")
endforeach()

add_test(NAME test_instructions_gate
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/gate.sh $<TARGET_FILE:dmbench_slowshader>
          ${DM_TEST_RUNS}/ci-gate)
set_tests_properties(test_instructions_gate PROPERTIES TIMEOUT 1800 FIXTURES_REQUIRED ci_gate_run
  ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;gate;valgrind")

# dmbench_plainshader: dmbench with a test-only copy of the GLSL whose
# vt.glsl has no virtual-texturing code (instructions/plain_vt.glsl).
# test_instructions_uber asserts that every technique with
# virtual_texture: off costs the same instructions with either binary.
dm_glsl_variant(plain ${CMAKE_CURRENT_SOURCE_DIR}/instructions/slow_glsl.cmake
  ARGS -DFAMILY=plainvt -DVT_FILE=${CMAKE_CURRENT_SOURCE_DIR}/instructions/plain_vt.glsl
  DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/instructions/plain_vt.glsl)

add_test(NAME test_instructions_uber
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/uber.sh $<TARGET_FILE:dmbench_plainshader>
          ${DM_TEST_RUNS}/ci-gate)
set_tests_properties(test_instructions_uber PROPERTIES TIMEOUT 1800 FIXTURES_REQUIRED ci_gate_run
  ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;gate;valgrind")

# A path configuration's Instructions: the mean frame of its replay, not
# its frame 0 (instructions/path.sh).
add_test(NAME test_instructions_path
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/path.sh)
set_tests_properties(test_instructions_path PROPERTIES TIMEOUT 1800
  ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;valgrind")

# Instructions repeat for each program family: three runs of a compact
# matrix (tests/instructions/repeat.yaml: normal, pom, vertex- and
# tess-displacement, reference-mesh), two from empty caches and one warm, in
# other orders, agree within 0.01 % (docs/counters.md, "Repeatability"):
# every count within 1e-4 (measured 2.5e-6 at worst).  One ctest test per
# run, so the two cold runs (which JIT every shader under Valgrind) go side
# by side; the warm run follows the first cold one (its caches), and
# test_instructions_repeat checks the three.
set(repeat_dir ${DM_TEST_RUNS}/repeat)
foreach(step cold1 cold2 warm)
  add_test(NAME test_instructions_repeat_${step}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/repeat.sh --run ${step} ${repeat_dir})
  set_tests_properties(test_instructions_repeat_${step} PROPERTIES TIMEOUT 1800
    ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;valgrind")
endforeach()
set_tests_properties(test_instructions_repeat_cold1 PROPERTIES FIXTURES_SETUP repeat_cold1)
set_tests_properties(test_instructions_repeat_cold2 PROPERTIES FIXTURES_SETUP repeat_runs)
set_tests_properties(test_instructions_repeat_warm PROPERTIES FIXTURES_SETUP repeat_runs
  FIXTURES_REQUIRED repeat_cold1)
add_test(NAME test_instructions_repeat
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/repeat.sh --check ${repeat_dir})
set_tests_properties(test_instructions_repeat PROPERTIES TIMEOUT 300
  FIXTURES_REQUIRED "repeat_cold1;repeat_runs" ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;valgrind")

# The fragment techniques repeat.yaml leaves out (one configuration of each
# program family is counted from empty caches there) repeat between two
# processes: the gate's run and the stage run share eight configurations
# key for key: each run's samples within 1e-4, the two runs within 1e-4 or
# 200 instructions a frame (instructions/repeat_across.py).
add_test(NAME test_instructions_repeat_across
  COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/instructions/repeat_across.py
          ${DM_TEST_RUNS}/ci-gate/baseline-techniques ${DM_TEST_RUNS}/stages-cube)
set_tests_properties(test_instructions_repeat_across PROPERTIES TIMEOUT 120
  FIXTURES_REQUIRED "ci_gate_run;stage_run_cube" LABELS "e2e;valgrind")

add_test(NAME test_instructions_families
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/families.sh
          $<TARGET_FILE:dmbench_slowvertexshader> $<TARGET_FILE:dmbench_slowtessshader> ${DM_TEST_RUNS}/stages-cube)
set_tests_properties(test_instructions_families PROPERTIES TIMEOUT 1800 FIXTURES_REQUIRED stage_run_cube
  ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;gate;valgrind")

# Stage costs (docs/counters.md, "Stage costs"): every technique's
# geometry + raster + fragment instructions add up to Instructions with a
# residual under 1 %, and on the full-screen quad fragment instructions are
# linear in the covered pixels (tests/stages/stages.sh, on the runs of the
# fixtures stage_run_cube, stage_run_reference and stage_run_fullscreen).
add_test(NAME test_stage_instructions
  COMMAND bash ${CMAKE_SOURCE_DIR}/tests/stages/stages.sh ${DM_TEST_RUNS}/stages-fullscreen
          ${DM_TEST_RUNS}/stages-cube ${DM_TEST_RUNS}/stages-reference)
set_tests_properties(test_stage_instructions PROPERTIES TIMEOUT 300
  FIXTURES_REQUIRED "stage_run_cube;stage_run_reference;stage_run_fullscreen"
  ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;valgrind")

# dmbench predict: a held-out resolution and step count within 5 % of the
# measured Instructions, a variant never measured listed, another machine
# and a missing counter refused (tests/stages/predict.sh).
# Its two counted runs (predict_fit.yaml, predict_new.yaml) are fixtures
# made side by side (test_predict_run_fit, test_predict_run_new); predict.sh
# copies them (PREDICT_RUNS) before it changes the fitted run's store.
foreach(part fit new)
  add_test(NAME test_predict_run_${part}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/fixture_run.sh ${DM_TEST_RUNS}/predict/${part}
            ${CMAKE_CURRENT_SOURCE_DIR}/stages/predict_${part}.yaml)
  set_tests_properties(test_predict_run_${part} PROPERTIES TIMEOUT 1800 FIXTURES_SETUP predict_run_${part}
    ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;valgrind")
endforeach()
add_test(NAME test_predict COMMAND bash ${CMAKE_SOURCE_DIR}/tests/stages/predict.sh)
set_tests_properties(test_predict PROPERTIES TIMEOUT 600 FIXTURES_REQUIRED "predict_run_fit;predict_run_new"
  ENVIRONMENT "${DM_TEST_ENV};PREDICT_RUNS=${DM_TEST_RUNS}/predict" LABELS "e2e;valgrind")

# The timed stage split: GeometryTime, MinimalShadingTime and the derived
# SetupRasterTime and FragmentTime (tests/stages/times.sh, no Valgrind).
add_test(NAME test_stage_times COMMAND bash ${CMAKE_SOURCE_DIR}/tests/stages/times.sh)
set_tests_properties(test_stage_times PROPERTIES TIMEOUT 120 ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e")

# LoopTrips counted by hand on the full-screen quad with the flat height
# map: steps/2 trips for every SIMD group (tests/stages/loop_trips.sh, no
# Valgrind).
add_test(NAME test_loop_trips COMMAND bash ${CMAKE_SOURCE_DIR}/tests/stages/loop_trips.sh)
set_tests_properties(test_loop_trips PROPERTIES TIMEOUT 120 ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e"
  SKIP_RETURN_CODE 77)
