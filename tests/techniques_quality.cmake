# Quality truth (techniques/ against the reference mesh, scored with reports/
# metrics): the ladder of the literature, POM convergence, tessellation level,
# normal maps following height_scale, and the render defects of issue 16.
# Images of a failing check go to quality-images/ in the build tree.
dm_add_gl(test_techniques_quality test_techniques_quality.c tech_fixture.c tech_spec.c
          LIBS dm_techniques dm_imaging TIMEOUT 900 NOQUICK)
target_compile_definitions(test_techniques_quality PRIVATE
    TECHQ_IMG_DIR="${CMAKE_CURRENT_BINARY_DIR}/quality-images")
