# The command line (cli/): the option parser and command table as a unit
# test; every option in help, man page, completion and parser alike; bash
# completion under bash; --json on every list; `dmbench diff`; `cmake --install`.
dm_add_unit(test_cli_parser test_cli_parser.c LIBS dm_cli LABELS cli)
set(cli_env ${DM_TEST_ENV} "DMBENCH_MAN=${CMAKE_BINARY_DIR}/dmbench.1"
    "DMBENCH_BASH_COMPLETION=${CMAKE_BINARY_DIR}/completions/dmbench")
# test_cli_options (~50 s: every option of every command, ~70 starts of the
# binary) stays out of the quick tier.
foreach(t options completion lists keys diff didyoumean)
  add_test(NAME test_cli_${t} COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/${t}.sh)
  set(labels cli quick)
  if(t STREQUAL options)
    set(labels cli)
  endif()
  set_tests_properties(test_cli_${t} PROPERTIES TIMEOUT 300 LABELS "${labels}" ENVIRONMENT "${cli_env}")
endforeach()
add_test(NAME test_cli_install COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/install.sh ${CMAKE_BINARY_DIR})
set_tests_properties(test_cli_install PROPERTIES TIMEOUT 300 LABELS "cli;quick")
# `dmbench predict`'s table, --json and --csv on runs given exact
# Instructions without Valgrind (tests/cli/predict_fixture.py; ~30 s).
add_test(NAME test_cli_predict_json COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/predict_json.sh)
set_tests_properties(test_cli_predict_json PROPERTIES TIMEOUT 600 LABELS e2e ENVIRONMENT "${DM_TEST_ENV}")
