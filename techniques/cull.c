/* cull.c — chunked CPU culling of triangle lists (see cull.h). */
#include "techniques/cull.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"

int cull_build(const mesh_data *m, size_t tris_per_chunk, cull_set *out)
{
    memset(out, 0, sizeof *out);
    size_t tris = m ? m->n_indices / 3 : 0;
    if (!tris || !tris_per_chunk)
        return DM_ERR_ARG;
    out->n = (tris + tris_per_chunk - 1) / tris_per_chunk;
    out->chunks = dm_xcalloc(out->n, sizeof *out->chunks);
    for (size_t c = 0; c < out->n; c++) {
        cull_chunk *k = &out->chunks[c];
        k->first = 3 * c * tris_per_chunk;
        k->count = 3 * (c + 1 < out->n ? tris_per_chunk : tris - c * tris_per_chunk);
        for (int a = 0; a < 3; a++) {
            k->lo[a] = FLT_MAX;
            k->hi[a] = -FLT_MAX;
        }
        for (size_t i = k->first; i < k->first + k->count; i++) {
            const float *p = m->vertices[m->indices[i]].pos;
            for (int a = 0; a < 3; a++) {
                k->lo[a] = p[a] < k->lo[a] ? p[a] : k->lo[a];
                k->hi[a] = p[a] > k->hi[a] ? p[a] : k->hi[a];
            }
        }
    }
    return 0;
}

/* 1 when all eight corners of the padded box lie beyond one plane of the
 * widened clip volume. */
static int cull__outside(const cull_chunk *k, const float mvp[16], float pad, float margin)
{
    int beyond[6] = {1, 1, 1, 1, 1, 1};
    for (int corner = 0; corner < 8; corner++) {
        float p[3], c[4];
        for (int a = 0; a < 3; a++)
            p[a] = corner >> a & 1 ? k->hi[a] + pad : k->lo[a] - pad;
        for (int r = 0; r < 4; r++)
            c[r] = mvp[r] * p[0] + mvp[4 + r] * p[1] + mvp[8 + r] * p[2] + mvp[12 + r];
        float w = c[3] * (1.0f + margin);
        for (int a = 0; a < 3; a++) {
            beyond[2 * a] &= c[a] < -w;
            beyond[2 * a + 1] &= c[a] > w;
        }
    }
    for (int i = 0; i < 6; i++)
        if (beyond[i])
            return 1;
    return 0;
}

size_t cull_visible(const cull_set *s, const float mvp[16], float pad, float margin,
                    size_t *first, size_t *count)
{
    size_t n = 0;
    for (size_t c = 0; c < s->n; c++) {
        const cull_chunk *k = &s->chunks[c];
        if (cull__outside(k, mvp, pad, margin))
            continue;
        if (n && first[n - 1] + count[n - 1] == k->first) {
            count[n - 1] += k->count;
            continue;
        }
        first[n] = k->first;
        count[n++] = k->count;
    }
    return n;
}

void cull_free(cull_set *s)
{
    free(s->chunks);
    memset(s, 0, sizeof *s);
}
