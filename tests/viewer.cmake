# The interactive viewer (viewer/ and cli/cmd_view.c): input, scripts and font without
# GL; the real binary in a virtual X server (tests/test_viewer.sh).
dm_add_unit(test_viewer_state test_viewer_state.c LIBS dm_viewer LABELS viewer)
add_executable(test_viewer_imgcmp test_viewer_imgcmp.c)
target_link_libraries(test_viewer_imgcmp PRIVATE dm_imaging dm_core m)
set(viewer_env ${DM_TEST_ENV} "VIEWER_IMGCMP=$<TARGET_FILE:test_viewer_imgcmp>")
if(DM_SANITIZE)
  # llvmpipe's first-draw JIT leak (see dm_add_gl): leak checks off for GL runs.
  list(APPEND viewer_env "ASAN_OPTIONS=detect_leaks=0")
endif()
foreach(mode batch-equal key-script timed config no-display light-normals)
  add_test(NAME test_viewer_${mode} COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test_viewer.sh ${mode})
  set_tests_properties(test_viewer_${mode} PROPERTIES TIMEOUT 300 LABELS viewer
    ENVIRONMENT "${viewer_env}")
endforeach()
