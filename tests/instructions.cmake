# The Instructions pass and the gate on it (run/callgrind.c, gate/): real
# runs under Valgrind callgrind of ci/gate.yaml (4 tiny configurations).
#
# dmbench_slowshader is dmbench with a test-only copy of the GLSL whose
# surface fragment shader does DM_SLOW_STEPS more steps per fragment
# (tests/instructions/slow_glsl.cmake); its embedded shader table replaces
# the real one at link time (an object given to the linker wins over the
# archive member defining the same table).  No production code path reads
# anything that makes shaders slower.
set(DM_SLOW_STEPS 1)
file(GLOB DM_SLOW_GLSL_IN CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/techniques/glsl/*.glsl)
set(DM_SLOW_DIR ${CMAKE_CURRENT_BINARY_DIR}/slow_glsl)
set(DM_SLOW_C ${CMAKE_CURRENT_BINARY_DIR}/shaders_slow.c)
add_custom_command(OUTPUT ${DM_SLOW_C}
  COMMAND ${CMAKE_COMMAND} -DGLSL_DIR=${CMAKE_SOURCE_DIR}/techniques/glsl -DOUT_DIR=${DM_SLOW_DIR}
          -DSTEPS=${DM_SLOW_STEPS} -P ${CMAKE_CURRENT_SOURCE_DIR}/instructions/slow_glsl.cmake
  COMMAND ${CMAKE_COMMAND} -DGLSL_DIR=${DM_SLOW_DIR} -DOUT=${DM_SLOW_C}
          -P ${CMAKE_SOURCE_DIR}/cmake/embed_glsl.cmake
  DEPENDS ${DM_SLOW_GLSL_IN} ${CMAKE_CURRENT_SOURCE_DIR}/instructions/slow_glsl.cmake
          ${CMAKE_SOURCE_DIR}/cmake/embed_glsl.cmake
  COMMENT "Embedding the test-only slower GLSL")
add_executable(dmbench_slowshader ${CMAKE_SOURCE_DIR}/cli/main.c ${DM_SLOW_C})
target_link_libraries(dmbench_slowshader PRIVATE dm_cli)

add_test(NAME test_instructions_gate
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/gate.sh $<TARGET_FILE:dmbench_slowshader>)
set_tests_properties(test_instructions_gate PROPERTIES TIMEOUT 1800
  ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;gate;valgrind")

# dmbench_plainshader: dmbench with a test-only copy of the GLSL whose
# vt.glsl has no virtual-texturing code (instructions/plain_vt.glsl).
# test_instructions_uber asserts that every technique with
# virtual_texture: off costs the same instructions with either binary.
set(DM_PLAIN_DIR ${CMAKE_CURRENT_BINARY_DIR}/plain_glsl)
set(DM_PLAIN_C ${CMAKE_CURRENT_BINARY_DIR}/shaders_plain.c)
add_custom_command(OUTPUT ${DM_PLAIN_C}
  COMMAND ${CMAKE_COMMAND} -E copy_directory ${CMAKE_SOURCE_DIR}/techniques/glsl ${DM_PLAIN_DIR}
  COMMAND ${CMAKE_COMMAND} -E copy ${CMAKE_CURRENT_SOURCE_DIR}/instructions/plain_vt.glsl ${DM_PLAIN_DIR}/vt.glsl
  COMMAND ${CMAKE_COMMAND} -DGLSL_DIR=${DM_PLAIN_DIR} -DOUT=${DM_PLAIN_C}
          -P ${CMAKE_SOURCE_DIR}/cmake/embed_glsl.cmake
  DEPENDS ${DM_SLOW_GLSL_IN} ${CMAKE_CURRENT_SOURCE_DIR}/instructions/plain_vt.glsl
          ${CMAKE_SOURCE_DIR}/cmake/embed_glsl.cmake
  COMMENT "Embedding the test-only GLSL without virtual texturing")
add_executable(dmbench_plainshader ${CMAKE_SOURCE_DIR}/cli/main.c ${DM_PLAIN_C})
target_link_libraries(dmbench_plainshader PRIVATE dm_cli)

add_test(NAME test_instructions_uber
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/instructions/uber.sh $<TARGET_FILE:dmbench_plainshader>)
set_tests_properties(test_instructions_uber PROPERTIES TIMEOUT 1800
  ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;gate;valgrind")
