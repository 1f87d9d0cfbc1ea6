/* user_mesh.c — meshes from files through Assimp (see user_mesh.h). */
#include "techniques/user_mesh.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"

/* Appends the triangles of one Assimp mesh; returns 1 when it supplied its
 * own tangents. */
static int user_mesh__append(const struct aiMesh *am, mesh_data *m)
{
    size_t base = m->n_vertices, tris = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++)
        tris += am->mFaces[f].mNumIndices == 3;
    m->vertices = dm_xrealloc(m->vertices, (base + am->mNumVertices) * sizeof(mesh_vertex));
    m->indices = dm_xrealloc(m->indices, (m->n_indices + 3 * tris + 1) * sizeof(uint32_t));
    int tangents = am->mTangents != NULL && am->mNormals != NULL;
    for (unsigned i = 0; i < am->mNumVertices; i++) {
        mesh_vertex *v = &m->vertices[base + i];
        memset(v, 0, sizeof *v);
        v->pos[0] = am->mVertices[i].x;
        v->pos[1] = am->mVertices[i].y;
        v->pos[2] = am->mVertices[i].z;
        if (am->mNormals) {
            v->nrm[0] = am->mNormals[i].x;
            v->nrm[1] = am->mNormals[i].y;
            v->nrm[2] = am->mNormals[i].z;
        }
        if (am->mTextureCoords[0]) {
            v->uv[0] = am->mTextureCoords[0][i].x;
            v->uv[1] = am->mTextureCoords[0][i].y;
        }
        if (tangents) {
            const struct aiVector3D *t = &am->mTangents[i], *n = &am->mNormals[i];
            v->tan[0] = t->x;
            v->tan[1] = t->y;
            v->tan[2] = t->z;
            float c[3] = {n->y * t->z - n->z * t->y, n->z * t->x - n->x * t->z, n->x * t->y - n->y * t->x};
            float s = am->mBitangents ? c[0] * am->mBitangents[i].x + c[1] * am->mBitangents[i].y +
                                            c[2] * am->mBitangents[i].z : 1.0f;
            v->tan[3] = s < 0 ? -1.0f : 1.0f;
        }
    }
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        const struct aiFace *face = &am->mFaces[f];
        if (face->mNumIndices != 3)
            continue;
        for (int k = 0; k < 3; k++)
            m->indices[m->n_indices++] = (uint32_t)(base + face->mIndices[k]);
    }
    m->n_vertices = base + am->mNumVertices;
    return tangents;
}

/* Centres the mesh and scales its longest bounding-box side to 2. */
static void user_mesh__fit(mesh_data *m)
{
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    for (size_t i = 0; i < m->n_vertices; i++)
        for (int a = 0; a < 3; a++) {
            lo[a] = fminf(lo[a], m->vertices[i].pos[a]);
            hi[a] = fmaxf(hi[a], m->vertices[i].pos[a]);
        }
    float ext = fmaxf(hi[0] - lo[0], fmaxf(hi[1] - lo[1], hi[2] - lo[2]));
    float s = ext > 0 ? 2.0f / ext : 1.0f;
    for (size_t i = 0; i < m->n_vertices; i++)
        for (int a = 0; a < 3; a++)
            m->vertices[i].pos[a] = (m->vertices[i].pos[a] - 0.5f * (lo[a] + hi[a])) * s;
}

/* Names the first attribute a triangle mesh of sc lacks (normals, then
 * texture coordinates), or NULL when every one has both. */
static const char *user_mesh__missing(const struct aiScene *sc, unsigned *which)
{
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *am = sc->mMeshes[i];
        if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
            continue;
        *which = i;
        if (!am->mNormals)
            return "normals (vn lines in an OBJ)";
        if (!am->mTextureCoords[0])
            return "texture coordinates (vt lines in an OBJ)";
    }
    return NULL;
}

int user_mesh_check(const char *path, dm_str *err)
{
    char why[256];
    if (dm_input_file(path, why, sizeof why) != 0) {   /* never open a FIFO or /dev/zero */
        dm_str_cat(err, why);
        return DM_ERR_IO;
    }
    const struct aiScene *sc = aiImportFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
    if (!sc) {
        dm_str_printf(err, "Assimp cannot read it: %s", aiGetErrorString());
        return DM_ERR_IO;
    }
    unsigned which = 0, tris = 0;
    for (unsigned i = 0; i < sc->mNumMeshes; i++)
        tris += (sc->mMeshes[i]->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) != 0;
    const char *missing = user_mesh__missing(sc, &which);
    if (tris == 0)
        dm_str_printf(err, "it holds no triangles (faces of 3 or more vertices)");
    else if (missing)
        dm_str_printf(err, "its mesh %u ('%s') has no %s; every technique needs them for its "
                      "tangent frame", which, sc->mMeshes[which]->mName.data, missing);
    aiReleaseImport(sc);
    return tris == 0 || missing ? DM_ERR_PARSE : 0;
}

int user_mesh_load(const char *path, mesh_data *out, int *had_tangents, dm_str *err)
{
    if (!path || !out)
        return DM_ERR_ARG;
    char why[256];
    if (dm_input_file(path, why, sizeof why) != 0) {
        if (err)
            dm_str_printf(err, "cannot load mesh '%s': %s\n", path, why);
        return DM_ERR_IO;
    }
    const struct aiScene *sc = aiImportFile(path, aiProcess_Triangulate | aiProcess_SortByPType |
                                                      aiProcess_PreTransformVertices |
                                                      aiProcess_GenSmoothNormals);
    if (!sc) {
        if (err)
            dm_str_printf(err, "cannot load mesh '%s': %s\n", path, aiGetErrorString());
        return DM_ERR_IO;
    }
    mesh_data m = {0};
    int all_tangents = 1;
    for (unsigned i = 0; i < sc->mNumMeshes; i++)
        if (sc->mMeshes[i]->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)
            all_tangents &= user_mesh__append(sc->mMeshes[i], &m);
    aiReleaseImport(sc);
    if (m.n_indices == 0) {
        mesh_free(&m);
        if (err)
            dm_str_printf(err, "mesh '%s' holds no triangles\n", path);
        return DM_ERR_PARSE;
    }
    user_mesh__fit(&m);
    if (!all_tangents)
        mesh_generate_tangents(&m);
    if (had_tangents)
        *had_tangents = all_tangents;
    *out = m;
    return 0;
}
