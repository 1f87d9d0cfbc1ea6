# Tests of the techniques layer (meshes, maps, axes, registry, renderer).
dm_add_unit(test_techniques_mesh test_techniques_mesh.c LIBS dm_techniques)
dm_add_unit(test_techniques_maps test_techniques_maps.c LIBS dm_techniques)
dm_add_unit(test_techniques_axes test_techniques_axes.c LIBS dm_techniques)
dm_add_unit(test_techniques_fs_minimal test_techniques_fs_minimal.c LIBS dm_techniques)
dm_add_unit(test_techniques_user test_techniques_user.c LIBS dm_techniques)
dm_add_gl(test_techniques_render test_techniques_render.c tech_fixture.c tech_spec.c LIBS dm_techniques)
dm_add_gl(test_techniques_invariants test_techniques_invariants.c tech_fixture.c tech_spec.c LIBS dm_techniques)
dm_add_gl(test_techniques_lights test_techniques_lights.c tech_fixture.c tech_spec.c LIBS dm_techniques)
