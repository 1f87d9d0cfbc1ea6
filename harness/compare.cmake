# The regression gate (SPEC §9): `dmbench compare` and `dmbench baseline`.
# The engine is an object library so that dm_harness (through
# DM_COMPARE_SOURCES) and the unit tests (through dm_compare) share one
# compilation; env.c gives dm_compare the fingerprint keys.
add_library(dm_compare_obj OBJECT
  ${CMAKE_CURRENT_LIST_DIR}/compare.c ${CMAKE_CURRENT_LIST_DIR}/compare_write.c
  ${CMAKE_CURRENT_LIST_DIR}/compare_input.c ${CMAKE_CURRENT_LIST_DIR}/compare_paired.c)
target_link_libraries(dm_compare_obj PUBLIC dm_store dm_reports dm_models dm_core PkgConfig::CJSON)
add_library(dm_compare STATIC $<TARGET_OBJECTS:dm_compare_obj> ${CMAKE_CURRENT_LIST_DIR}/env.c)
target_link_libraries(dm_compare PUBLIC dm_store dm_reports dm_models dm_core PkgConfig::CJSON
  PkgConfig::EPOXY m)
set(DM_COMPARE_SOURCES cli_compare.c $<TARGET_OBJECTS:dm_compare_obj>)
