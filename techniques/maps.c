/* maps.c — procedural material maps (see maps.h). */
#include "techniques/maps.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"

#define MAPS__ROWS 8          /* brick rows per tile */
#define MAPS__COLS 4          /* bricks per row */
#define MAPS__MORTAR 0.008f   /* mortar half-width in UV units */
#define MAPS__BEVEL 0.014f    /* bevel width in UV units */
#define MAPS__NOISE_CELLS 32  /* value-noise lattice cells per tile (tiles seamlessly) */

static const char *const maps__names[] = {"bricks", "flat", NULL};

const char *const *maps_names(void) { return maps__names; }

/* Deterministic hash of a lattice point into [0,1). */
static float maps__hash(uint32_t x, uint32_t y, uint32_t seed)
{
    uint32_t k[3] = {x, y, seed};
    return (float)(dm_fnv1a64(k, sizeof k, DM_FNV_SEED) >> 40) / (float)(1u << 24);
}

/* Periodic value noise in [0,1) at (u,v) in tile units. */
static float maps__noise(float u, float v)
{
    float x = u * MAPS__NOISE_CELLS, y = v * MAPS__NOISE_CELLS;
    float fx = x - floorf(x), fy = y - floorf(y);
    uint32_t ix = (uint32_t)floorf(x) % MAPS__NOISE_CELLS, iy = (uint32_t)floorf(y) % MAPS__NOISE_CELLS;
    uint32_t jx = (ix + 1) % MAPS__NOISE_CELLS, jy = (iy + 1) % MAPS__NOISE_CELLS;
    fx = fx * fx * (3 - 2 * fx);
    fy = fy * fy * (3 - 2 * fy);
    float a = maps__hash(ix, iy, 7), b = maps__hash(jx, iy, 7);
    float c = maps__hash(ix, jy, 7), d = maps__hash(jx, jy, 7);
    return (a + (b - a) * fx) + ((c + (d - c) * fx) - (a + (b - a) * fx)) * fy;
}

/* Height and albedo of the brick pattern at (u,v) ∈ [0,1)². */
static void maps__brick(float u, float v, float *h, float rgba[4])
{
    float by = v * MAPS__ROWS, row = floorf(by), fy = by - row;
    float bx = u * MAPS__COLS + (fmodf(row, 2) ? 0.5f : 0), col = floorf(bx), fx = bx - col;
    float dx = fminf(fx, 1 - fx) / MAPS__COLS, dy = fminf(fy, 1 - fy) / MAPS__ROWS;
    float d = fminf(dx, dy), n = maps__noise(u, v);
    float id = maps__hash((uint32_t)col % MAPS__COLS, (uint32_t)row, 3);
    float t = (d - MAPS__MORTAR) / MAPS__BEVEL;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    t = t * t * (3 - 2 * t);
    *h = 0.12f + 0.06f * n + t * (0.68f + 0.08f * id);
    float m[3] = {0.62f, 0.60f, 0.56f}, br[3] = {0.58f, 0.24f, 0.16f};
    float shade = 0.8f + 0.4f * id;
    for (int i = 0; i < 3; i++)
        rgba[i] = (m[i] + (br[i] * shade - m[i]) * t) * (0.9f + 0.2f * n);
    rgba[3] = 1;
}

void maps_normal_from_height(const float *height, int size, float strength, float *normal)
{
    float s = strength * MAPS_NORMAL_SCALE * (float)size * 0.5f;
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            int xm = (x + size - 1) % size, xp = (x + 1) % size;
            int ym = (y + size - 1) % size, yp = (y + 1) % size;
            float gx = s * (height[y * size + xp] - height[y * size + xm]);
            float gy = s * (height[yp * size + x] - height[ym * size + x]);
            float l = sqrtf(gx * gx + gy * gy + 1);
            float *n = &normal[3 * ((size_t)y * (size_t)size + (size_t)x)];
            n[0] = -gx / l;
            n[1] = -gy / l;
            n[2] = 1 / l;
        }
}

static void maps__fill(maps_set *m, int bricks)
{
    int n = m->size;
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            size_t i = (size_t)y * (size_t)n + (size_t)x;
            if (bricks) {
                maps__brick(((float)x + 0.5f) / (float)n, ((float)y + 0.5f) / (float)n,
                            &m->height[i], &m->albedo[4 * i]);
                continue;
            }
            m->height[i] = 0.5f;
            for (int c = 0; c < 4; c++)
                m->albedo[4 * i + (size_t)c] = c == 3 ? 1.0f : 0.75f;
        }
}

int maps_generate(const maps_desc *desc, maps_set *out)
{
    const char *name = desc && desc->name ? desc->name : "bricks";
    int size = desc && desc->size ? desc->size : 512;
    float strength = desc && desc->normal_strength != 0 ? desc->normal_strength : 1.0f;
    int kind = -1;
    for (int i = 0; maps__names[i]; i++)
        if (strcmp(name, maps__names[i]) == 0)
            kind = i;
    if (kind < 0)
        return DM_ERR_UNKNOWN;
    if (size < MAPS_MIN_SIZE || size > MAPS_MAX_SIZE)
        return DM_ERR_RANGE;
    size_t texels = (size_t)size * (size_t)size;
    out->size = size;
    out->height = dm_xmalloc(texels * sizeof(float));
    out->normal = dm_xmalloc(texels * 3 * sizeof(float));
    out->albedo = dm_xmalloc(texels * 4 * sizeof(float));
    maps__fill(out, kind == 0);
    maps_normal_from_height(out->height, size, strength, out->normal);
    return 0;
}

void maps_free(maps_set *m)
{
    if (!m)
        return;
    free(m->height);
    free(m->normal);
    free(m->albedo);
    memset(m, 0, sizeof *m);
}
