# Reports layer tests (reports/): image bridge, quality metrics, report files.
dm_add_unit(test_reports_image test_reports_image.c LIBS dm_imaging)
dm_add_unit(test_reports_quality test_reports_quality.c LIBS dm_imaging)
# Temporal stability of a sequence against its reference (imaging/temporal.h).
dm_add_unit(test_imaging_temporal test_imaging_temporal.c LIBS dm_imaging)
dm_add_unit(test_reports_flip test_reports_flip.c LIBS dm_reports dm_imaging)
dm_add_unit(test_reports_report test_reports_report.c LIBS dm_reports)
dm_add_unit(test_reports_recommend test_reports_recommend.c LIBS dm_reports)
dm_add_unit(test_reports_proxy test_reports_proxy.c LIBS dm_reports)
dm_add_unit(test_reports_drivers test_reports_drivers.c LIBS dm_reports)
dm_add_unit(test_reports_stage_bar test_reports_stage_bar.c LIBS dm_reports)

# Browser test: a generated report opened in headless chromium (tests/browser/).
add_executable(test_reports_browser_gen browser/gen_report.c)
target_link_libraries(test_reports_browser_gen PRIVATE dm_reports dm_core m)
add_test(NAME test_reports_browser
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/browser/report_in_chromium.sh $<TARGET_FILE:test_reports_browser_gen>)
set_tests_properties(test_reports_browser PROPERTIES TIMEOUT 60 LABELS "browser")

# The default quick run's report in chromium: the front table in the first
# screen at 1280x800 and 1920x1080, no clipped chart text, under 2 MB; the
# screenshots stay in build/artifacts/report-screenshots (CI artefacts).
# The run is a copy of the suite's (fixture quick_runs, tests/e2e.cmake).
add_test(NAME test_reports_quick_browser
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/browser/quick_report.sh $<TARGET_FILE:dmbench>
          ${CMAKE_BINARY_DIR}/artifacts/report-screenshots ${DM_QUICK_RUNS})
set_tests_properties(test_reports_quick_browser PROPERTIES TIMEOUT 300 LABELS "browser;e2e"
  ENVIRONMENT "${DM_TEST_ENV}" FIXTURES_REQUIRED quick_runs)
dm_add_unit(test_reports_published test_reports_published.c LIBS dm_reports)
dm_add_unit(test_reports_model test_reports_model.c LIBS dm_reports)
