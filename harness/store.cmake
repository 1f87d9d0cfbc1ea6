# Results store (SQLite): the single source of results (SPEC §5).
add_library(dm_store STATIC ${CMAKE_CURRENT_LIST_DIR}/store.c)
target_link_libraries(dm_store PUBLIC dm_core PkgConfig::SQLITE)
