/* mesh_list.c — the built-in meshes, one row each: name, builder, default
 * density, and the range of an explicit density (mesh.h says what density
 * means for each).  mesh_build, mesh_density_range and mesh_names read
 * only this table; adding a mesh is one builder (mesh.c or mesh_scene.c)
 * and one row. */
#include "techniques/mesh.h"

#include <pthread.h>
#include <string.h>

#include "core/dm_error.h"
#include "techniques/mesh_internal.h"
#include "techniques/mesh_scene.h"

typedef struct mesh_list__row {
    const char *name;
    mesh__build_fn build;
    int def, lo, hi;    /* 0 stands for def; an explicit density lies in [lo, hi] */
} mesh_list__row;

/* In listing order: the single meshes, then the scenes (mesh_scene.h). */
static const mesh_list__row mesh_list__rows[] = {
    {"plane", mesh__build_plane, 2, 2, 1024},
    {"cube", mesh__build_cube, 0, 0, 1024},
    {"triangle", mesh__build_triangle, 0, 0, 1024},
    {"fullscreen", mesh__build_fullscreen, 0, 0, 1024},
    {"cylinder", mesh__build_cylinder, 58, 3, 1024},
    {"sphere", mesh__build_sphere, 4, 0, 7},
    {"terrain", mesh__build_terrain, 16, 1, 512},
    {"asteroid", mesh__build_asteroid, 6, 0, 7},
    {"seam", mesh__build_seam, 4, 1, 256},
    {"halfflat", mesh__build_halfflat, 4, 1, 256},
    {"asteroid-reduced", mesh__build_asteroid_reduced, 2, 0, 7},
    {"terrain-tiles", mesh__build_terrain_tiles, 8, 1, 256},
    {"s2-scene1", mesh_scene_build_s2, 0, 1, 0},   /* lo > hi: only 0 */
    {"s4-asteroids", mesh_scene_build_s4, 3, 1, 7},
    {"s4-asteroids-reduced", mesh_scene_build_s4_reduced, 2, 1, 7},
};
#define MESH_LIST__N (sizeof mesh_list__rows / sizeof mesh_list__rows[0])

static const char *mesh_list__names[MESH_LIST__N + 1];
static pthread_once_t mesh_list__once = PTHREAD_ONCE_INIT;

static void mesh_list__init_names(void)
{
    for (size_t i = 0; i < MESH_LIST__N; i++)
        mesh_list__names[i] = mesh_list__rows[i].name;
}

const char *const *mesh_names(void)
{
    pthread_once(&mesh_list__once, mesh_list__init_names);
    return mesh_list__names;
}

static const mesh_list__row *mesh_list__find(const char *name)
{
    for (size_t i = 0; i < MESH_LIST__N; i++)
        if (strcmp(mesh_list__rows[i].name, name) == 0)
            return &mesh_list__rows[i];
    return NULL;
}

int mesh_density_range(const char *name, int *def, int *lo, int *hi)
{
    const mesh_list__row *r = name ? mesh_list__find(name) : NULL;
    if (!r)
        return DM_ERR_UNKNOWN;
    *def = r->def;
    *lo = r->lo;
    *hi = r->hi;
    return 0;
}

int mesh_build(const mesh_desc *desc, mesh_data *out)
{
    const char *name = desc && desc->name ? desc->name : "plane";
    int d = desc ? desc->density : 0;
    const mesh_list__row *r = mesh_list__find(name);
    if (!r)
        return DM_ERR_UNKNOWN;
    if (d != 0 && (d < r->lo || d > r->hi))
        return DM_ERR_RANGE;
    return r->build(d ? d : r->def, out);
}
