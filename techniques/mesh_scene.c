/* mesh_scene.c — built-in scenes of several objects (see mesh_scene.h). */
#include "techniques/mesh_scene.h"
#include "techniques/mesh_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"

#define MESH_SCENE__PI 3.14159265358979323846f

static void mesh_scene__append(mesh_data *dst, const mesh_data *src, float scale, const float off[3],
                               int inward)
{
    size_t base = dst->n_vertices;
    dst->vertices = dm_xrealloc(dst->vertices, (base + src->n_vertices) * sizeof(mesh_vertex));
    dst->indices = dm_xrealloc(dst->indices, (dst->n_indices + src->n_indices) * sizeof(uint32_t));
    for (size_t i = 0; i < src->n_vertices; i++) {
        mesh_vertex v = src->vertices[i];
        for (int k = 0; k < 3; k++) {
            v.pos[k] = v.pos[k] * scale + off[k];
            v.nrm[k] = inward ? -v.nrm[k] : v.nrm[k];
        }
        dst->vertices[base + i] = v;
    }
    for (size_t i = 0; i < src->n_indices; i++) {
        size_t j = inward ? i - i % 3 + (2 - i % 3) : i;   /* (a,b,c) -> (c,b,a) */
        dst->indices[dst->n_indices + i] = (uint32_t)(base + src->indices[j]);
    }
    dst->n_vertices += src->n_vertices;
    dst->n_indices += src->n_indices;
}

/* Builds a single mesh with build at density and appends it placed. */
static int mesh_scene__object(mesh_data *dst, mesh__build_fn build, int density, float scale,
                              const float off[3], int inward)
{
    mesh_data m = {0};
    int rc = build(density, &m);
    if (rc == 0)
        mesh_scene__append(dst, &m, scale, off, inward);
    mesh_free(&m);
    return rc;
}

/* Torus around +Y: ring radius R, tube radius r, a × b quads, (a+1)(b+1)
 * vertices (seams duplicated), u = 4·i/a around the ring, v = j/b around
 * the tube; placed at off. */
static void mesh_scene__torus(mesh_data *dst, float R, float r, int a, int b, const float off[3])
{
    mesh_data t = {0};
    t.n_vertices = (size_t)(a + 1) * (size_t)(b + 1);
    t.vertices = dm_xcalloc(t.n_vertices, sizeof(mesh_vertex));
    t.indices = dm_xmalloc((size_t)a * (size_t)b * 6 * sizeof(uint32_t));
    for (int i = 0; i <= a; i++)
        for (int j = 0; j <= b; j++) {
            float th = 2 * MESH_SCENE__PI * (float)i / (float)a, ph = 2 * MESH_SCENE__PI * (float)j / (float)b;
            mesh_vertex *v = &t.vertices[(size_t)i * (size_t)(b + 1) + (size_t)j];
            float n[3] = {cosf(ph) * sinf(th), sinf(ph), cosf(ph) * cosf(th)};
            for (int k = 0; k < 3; k++)
                v->nrm[k] = n[k];
            v->pos[0] = (R + r * cosf(ph)) * sinf(th);
            v->pos[1] = r * sinf(ph);
            v->pos[2] = (R + r * cosf(ph)) * cosf(th);
            v->uv[0] = 4.0f * (float)i / (float)a;
            v->uv[1] = (float)j / (float)b;
        }
    for (int i = 0; i < a; i++)
        for (int j = 0; j < b; j++) {
            uint32_t p = (uint32_t)(i * (b + 1) + j), q = p + (uint32_t)(b + 1);
            uint32_t quad[6] = {p, q, q + 1, p, q + 1, p + 1};
            memcpy(&t.indices[t.n_indices], quad, sizeof quad);
            t.n_indices += 6;
        }
    mesh_scene__append(dst, &t, 1.0f, off, 0);
    mesh_free(&t);
}

/* S2's scene 1: plane 8 192 + sphere 5 120 + torus 8 774 = 22 086 triangles. */
static int mesh_scene__s2(mesh_data *out)
{
    static const float ground[3] = {0, -0.6f, 0}, ball[3] = {-0.42f, -0.28f, -0.3f},
                       ring[3] = {0.45f, -0.49f, 0.38f};
    int rc = mesh_scene__object(out, mesh__build_plane, 65, 1.0f, ground, 0);
    rc = rc ? rc : mesh_scene__object(out, mesh__build_sphere, 4, 0.32f, ball, 0);
    if (rc == 0)
        mesh_scene__torus(out, 0.3f, 0.11f, 107, 41, ring);
    return rc;
}

/* S4's scene: the inward skybox first, then the asteroids. */
static int mesh_scene__s4(mesh_data *out, mesh__build_fn body, int level)
{
    static const float at[MESH_SCENE_ASTEROIDS][3] = {
        {-0.6f, 0.1f, -0.3f}, {0.55f, -0.2f, 0.2f}, {0.05f, 0.5f, 0.5f},
        {-0.25f, -0.55f, 0.45f}, {0.5f, 0.55f, -0.5f}};
    int rc = mesh_scene__object(out, mesh__build_cube, 0, MESH_SCENE_SKYBOX, (const float[3]){0, 0, 0}, 1);
    for (int i = 0; rc == 0 && i < MESH_SCENE_ASTEROIDS; i++)
        rc = mesh_scene__object(out, body, level, MESH_SCENE_ASTEROID_SCALE, at[i], 0);
    return rc;
}

/* Tangents of a scene built into m, then out takes it; on failure m is freed. */
static int mesh_scene__finish(int rc, mesh_data *m, mesh_data *out)
{
    if (rc) {
        mesh_free(m);
        return rc;
    }
    mesh_generate_tangents(m);
    *out = *m;
    return 0;
}

int mesh_scene_build_s2(int d, mesh_data *out)
{
    (void)d;   /* s2-scene1 takes only 0 */
    mesh_data m = {0};
    return mesh_scene__finish(mesh_scene__s2(&m), &m, out);
}

int mesh_scene_build_s4(int d, mesh_data *out)
{
    mesh_data m = {0};
    return mesh_scene__finish(mesh_scene__s4(&m, mesh__build_asteroid, d), &m, out);
}

int mesh_scene_build_s4_reduced(int d, mesh_data *out)
{
    mesh_data m = {0};
    return mesh_scene__finish(mesh_scene__s4(&m, mesh__build_asteroid_reduced, d), &m, out);
}
