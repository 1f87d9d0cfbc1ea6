# Tests of the axes of the studies' missing experiments (issue 19): CPU
# distance LOD, separate inner/outer levels, face culling, S1 attenuation,
# vertex-fetch height format, parallax bias.
dm_add_gl(test_techniques_experiments_gl test_techniques_experiments_gl.c tech_fixture.c tech_spec.c LIBS dm_techniques)
