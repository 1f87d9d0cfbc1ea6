# Tests of the geometry techniques (meshes, tessellation and vertex
# displacement, reference mesh, user meshes through Assimp).
dm_add_unit(test_techniques_geometry_mesh test_techniques_geometry_mesh.c LIBS dm_techniques)
dm_add_gl(test_techniques_geometry_gl test_techniques_geometry_gl.c tech_fixture.c tech_spec.c LIBS dm_techniques dm_imaging)
dm_add_gl(test_techniques_cylinder_caps test_techniques_cylinder_caps.c tech_fixture.c tech_spec.c LIBS dm_techniques dm_imaging)
