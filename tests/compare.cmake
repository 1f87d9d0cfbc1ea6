# The regression gate (gate/): unit tests on synthetic runs and
# CLI tests with the real binary.
dm_add_unit(test_compare test_compare.c LIBS dm_compare)
add_test(NAME test_compare_cli COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/compare/cli.sh)
set_tests_properties(test_compare_cli PROPERTIES TIMEOUT 600 ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e")
# The percentage grammar of every fraction flag, on synthetic runs (no GL).
add_test(NAME test_compare_fractions COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/compare/fractions.sh)
set_tests_properties(test_compare_fractions PROPERTIES TIMEOUT 300 ENVIRONMENT "${DM_TEST_ENV}" LABELS quick)
# --markdown for a PR comment: always a file, --only-changed (no GL).
add_test(NAME test_compare_markdown COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/compare/markdown.sh)
set_tests_properties(test_compare_markdown PROPERTIES TIMEOUT 300 ENVIRONMENT "${DM_TEST_ENV}" LABELS quick)
# --markdown as a code review shows it: entities, whole notes, precision,
# signed change, machine lines, capped advice, --rounds minimum (no GL).
add_test(NAME test_compare_markdown_pr COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/compare/markdown_pr.sh)
set_tests_properties(test_compare_markdown_pr PROPERTIES TIMEOUT 300 ENVIRONMENT "${DM_TEST_ENV}" LABELS "e2e;quick")
