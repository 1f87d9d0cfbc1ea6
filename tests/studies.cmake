# The studies' pages (docs/reproductions.md, displacement.md, textures.md,
# studies.md): every ratio, verdict, published ratio and prose conclusion
# recomputed from the tables beside it (bench/study_claims.py), so prose and
# tables cannot drift apart; the drift test edits copies of the pages and
# requires each edit to be caught.
find_program(DM_PYTHON3 python3)
if(DM_PYTHON3)
  add_test(NAME test_study_claims
    COMMAND ${DM_PYTHON3} ${PROJECT_SOURCE_DIR}/bench/study_claims.py ${PROJECT_SOURCE_DIR})
  set_tests_properties(test_study_claims PROPERTIES TIMEOUT 30 LABELS "docs;quick")
  add_test(NAME test_study_claims_drift
    COMMAND ${DM_PYTHON3} ${PROJECT_SOURCE_DIR}/bench/study_claims.py --self-test ${PROJECT_SOURCE_DIR})
  set_tests_properties(test_study_claims_drift PROPERTIES TIMEOUT 60 LABELS "docs;quick")
else()
  message(STATUS "python3 not found: test_study_claims not registered")
endif()
