# Reports layer tests (reports/): image bridge, quality metrics, report files.
dm_add_unit(test_reports_image test_reports_image.c LIBS dm_reports)
dm_add_unit(test_reports_quality test_reports_quality.c LIBS dm_reports)
dm_add_unit(test_reports_report test_reports_report.c LIBS dm_reports)
dm_add_unit(test_reports_pareto test_reports_pareto.c LIBS dm_reports)
dm_add_unit(test_reports_proxy test_reports_proxy.c LIBS dm_reports)

# Browser test: a generated report opened in headless chromium (tests/browser/).
add_executable(test_reports_browser_gen browser/gen_report.c)
target_link_libraries(test_reports_browser_gen PRIVATE dm_reports dm_core m)
add_test(NAME test_reports_browser
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/browser/report_in_chromium.sh $<TARGET_FILE:test_reports_browser_gen>)
set_tests_properties(test_reports_browser PROPERTIES TIMEOUT 60 LABELS "browser")
