/* render_meshes.c — the renderer's meshes: built, displaced for the
 * reference, given their seam buffer, uploaded and cached (see
 * render_meshes.h). */
#include "techniques/render_meshes.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "techniques/maps.h"
#include "techniques/mesh.h"
#include "techniques/render_internal.h"
#include "techniques/technique.h"
#include "techniques/user_mesh.h"

/* Cache key of the item's mesh: name/density, plus the height field and
 * scale it was displaced with for cpu_displace techniques. */
static char *render__mesh_key(const technique_desc *t, const render__cfg *c)
{
    const char *name = render__get(c, "mesh"), *dens = render__get(c, "mesh_density");
    if (t->tcs)   /* patch meshes carry the seam buffer (render__mesh_seams) */
        return dm_xasprintf("%s/%d/patches", name, atoi(dens));
    if (!t->cpu_displace)
        return dm_xasprintf("%s/%d", name, atoi(dens));
    return dm_xasprintf("%s/%d/displaced:%s/%d/%.9g", name, atoi(dens), render__get(c, "maps"),
                        atoi(render__get(c, "texture_size")), atof(render__get(c, "height_scale")));
}

/* The reference mesh: `base` split k² per triangle (about
 * RENDER__REFERENCE_TRIANGLES in all) and displaced by the CPU height map
 * of the configuration's maps (generated, or the user's material files);
 * replaces *base.  A map that cannot be had says why in log. */
static int render__mesh_displace(const render__cfg *c, mesh_data *base, dm_str *log)
{
    maps_set ms;
    maps_desc md = {.name = render__get(c, "maps"), .size = atoi(render__get(c, "texture_size"))};
    int rc = maps_is_material(md.name) ? maps_material_load(md.name, &ms, log) : maps_generate(&md, &ms);
    if (rc) {
        dm_str_printf(log, "the reference's height map '%s': %s\n", md.name, dm_strerror(rc));
        return rc;
    }
    size_t tris = base->n_indices / 3 ? base->n_indices / 3 : 1;
    int k = (int)floor(sqrt((double)RENDER__REFERENCE_TRIANGLES / (double)tris));
    k = k < 1 ? 1 : k > 512 ? 512 : k;
    while (k > 1 && mesh_subdivide_cost(base, k) > 2 * (size_t)RENDER__REFERENCE_TRIANGLES)
        k--;   /* long edges get more splits (mesh.h): at most twice the budget */
    mesh_data out;
    rc = mesh_subdivide_displace(base, k, ms.height, ms.size,
                                 (float)atof(render__get(c, "height_scale")), &out);
    maps_free(&ms);
    if (!rc) {
        mesh_free(base);
        *base = out;
    }
    return rc;
}

/* Patch meshes: a second vertex buffer (binding 1) with each vertex's
 * canonical UV (attribute 4) and normal (attribute 5) — those of the first
 * vertex at its position (mesh_canonical) — which crack-free tessellation
 * uses on patch edges; counted in MeshBytes. */
static void render__mesh_seams(render__mesh *m, const mesh_data *md)
{
    size_t nv = md->n_vertices;
    float *buf = dm_xmalloc((nv + 1) * 5 * sizeof(float)), *uv = buf, *nrm = buf + 2 * nv;
    mesh_canonical(md, uv, nrm);
    glCreateBuffers(1, &m->seam_vbo);
    glNamedBufferStorage(m->seam_vbo, (GLsizeiptr)(nv * 5 * sizeof(float)), buf, 0);
    glVertexArrayVertexBuffer(m->vao, 1, m->seam_vbo, 0, 2 * sizeof(float));
    glVertexArrayVertexBuffer(m->vao, 2, m->seam_vbo, (GLintptr)(2 * nv * sizeof(float)), 3 * sizeof(float));
    for (GLuint a = 4; a < 6; a++) {
        glEnableVertexArrayAttrib(m->vao, a);
        glVertexArrayAttribFormat(m->vao, a, (GLint)(a == 4 ? 2 : 3), GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(m->vao, a, a - 3);
    }
    m->bytes += nv * 5 * sizeof(float);
    free(buf);
}

int render__mesh_get(render_ctx *r, const technique_desc *t, const render__cfg *c,
                     size_t *idx, dm_str *log)
{
    char *key = render__mesh_key(t, c);
    for (size_t i = 0; i < r->n_meshes; i++)
        if (strcmp(r->meshes[i].key, key) == 0) {
            free(key);
            *idx = i;
            return 0;
        }
    mesh_data md;
    mesh_desc d = {.name = render__get(c, "mesh"), .density = atoi(render__get(c, "mesh_density"))};
    int rc, had_tangents = 0;
    if (strncmp(d.name, USER_MESH_PREFIX, strlen(USER_MESH_PREFIX)) == 0)
        rc = user_mesh_load(d.name + strlen(USER_MESH_PREFIX), &md, &had_tangents, log);
    else
        rc = mesh_build(&d, &md);
    if (rc) {
        dm_str_printf(log, "mesh '%s' with density %d: %s\n", d.name, d.density, dm_strerror(rc));
        free(key);
        return rc;
    }
    if (t->cpu_displace && (rc = render__mesh_displace(c, &md, log)) != 0) {
        mesh_free(&md);
        free(key);
        return rc;
    }
    size_t n = RENDER__PUSH(r->meshes, r->n_meshes);
    render__mesh *m = &r->meshes[n];
    m->key = key;
    m->n_vertices = md.n_vertices;
    m->n_indices = md.n_indices;
    m->n_quad_indices = md.n_quad_indices;
    m->object_tris = md.object_triangles;
    m->cull = (cull_set){0};
    if (!md.clip_space && md.n_indices)
        cull_build(&md, RENDER__CULL_CHUNK, &m->cull);
    m->bytes = mesh_bytes(&md);
    m->clip_space = md.clip_space;
    float longest = 0;   /* the long-edge rule is tessellation's (tess.tcs.glsl) */
    m->edge_median = t->tcs ? mesh_edge_median(&md, &longest) : 0;
    m->edge_factor_max = mesh_edge_factor(longest, m->edge_median);
    glCreateVertexArrays(1, &m->vao);
    glCreateBuffers(1, &m->vbo);
    glCreateBuffers(1, &m->ibo);
    glNamedBufferStorage(m->vbo, (GLsizeiptr)(md.n_vertices * sizeof(mesh_vertex)), md.vertices, 0);
    glNamedBufferStorage(m->ibo, (GLsizeiptr)((md.n_indices + md.n_quad_indices) * sizeof(uint32_t)),
                         md.indices, 0);
    glVertexArrayVertexBuffer(m->vao, 0, m->vbo, 0, sizeof(mesh_vertex));
    glVertexArrayElementBuffer(m->vao, m->ibo);
    static const GLuint comps[4] = {3, 3, 2, 4};
    static const size_t offs[4] = {offsetof(mesh_vertex, pos), offsetof(mesh_vertex, nrm),
                                   offsetof(mesh_vertex, uv), offsetof(mesh_vertex, tan)};
    for (GLuint a = 0; a < 4; a++) {
        glEnableVertexArrayAttrib(m->vao, a);
        glVertexArrayAttribFormat(m->vao, a, (GLint)comps[a], GL_FLOAT, GL_FALSE, (GLuint)offs[a]);
        glVertexArrayAttribBinding(m->vao, a, 0);
    }
    if (t->tcs) {
        render__mesh_seams(m, &md);
        m->cpu_pos = dm_xmalloc(md.n_vertices * 3 * sizeof(float));
        for (size_t v = 0; v < md.n_vertices; v++)
            memcpy(m->cpu_pos + 3 * v, md.vertices[v].pos, 3 * sizeof(float));
        size_t ni = md.n_indices + md.n_quad_indices;
        m->cpu_idx = dm_xmalloc((ni ? ni : 1) * sizeof(uint32_t));
        memcpy(m->cpu_idx, md.indices, ni * sizeof(uint32_t));
    }
    mesh_free(&md);
    *idx = n;
    return 0;
}
