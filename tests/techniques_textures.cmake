# Tests of the texture half of the techniques layer (maps, formats, filters,
# cache, virtual texture).
dm_add_unit(test_techniques_textures test_techniques_textures.c LIBS dm_techniques)
dm_add_gl(test_techniques_textures_gl test_techniques_textures_gl.c tech_spec.c LIBS dm_techniques)
dm_add_gl(test_techniques_textures_vt test_techniques_textures_vt.c tech_spec.c LIBS dm_techniques)
dm_add_gl(test_techniques_textures_big test_techniques_textures_big.c LIBS dm_techniques
          TIMEOUT 600 LABELS slow)
