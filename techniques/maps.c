/* maps.c — procedural material maps and their disk cache (see maps.h). */
#include "techniques/maps.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "core/dm_image.h"
#include "core/dm_util.h"
#include "techniques/mesh.h"

#define MAPS__ROWS 8          /* brick rows per tile */
#define MAPS__COLS 4          /* bricks per row */
#define MAPS__MORTAR 0.008f   /* mortar half-width in UV units */
#define MAPS__BEVEL 0.014f    /* bevel width in UV units */
#define MAPS__NOISE_CELLS 32  /* value-noise lattice cells per tile (tiles seamlessly) */
#define MAPS__STONE_CELLS 8   /* cellular (Worley) cells per tile side */
#define MAPS__FBM_OCTAVES 6   /* terrain: lattices of 4, 8, ... 128 cells */
#define MAPS__CACHE_MAGIC "DMMAPS2"   /* 8 bytes with the NUL; bump when a generator or the layout changes */

/* One texel of a set: height, linear albedo RGB and specular at (u,v). */
typedef void (*maps__texel_fn)(float u, float v, float *h, float rgb[3], float *spec);

/* Deterministic hash of a lattice point into [0,1). */
static float maps__hash(uint32_t x, uint32_t y, uint32_t seed)
{
    uint32_t k[3] = {x, y, seed};
    return (float)(dm_fnv1a64(k, sizeof k, DM_FNV_SEED) >> 40) / (float)(1u << 24);
}

/* Periodic value noise in [0,1) at (u,v) in tile units on a cells² lattice. */
static float maps__noise(float u, float v, int cells, uint32_t seed)
{
    uint32_t n = (uint32_t)cells;
    float x = u * (float)cells, y = v * (float)cells;
    float fx = x - floorf(x), fy = y - floorf(y);
    uint32_t ix = (uint32_t)floorf(x) % n, iy = (uint32_t)floorf(y) % n;
    uint32_t jx = (ix + 1) % n, jy = (iy + 1) % n;
    fx = fx * fx * (3 - 2 * fx);
    fy = fy * fy * (3 - 2 * fy);
    float a = maps__hash(ix, iy, seed), b = maps__hash(jx, iy, seed);
    float c = maps__hash(ix, jy, seed), d = maps__hash(jx, jy, seed);
    return (a + (b - a) * fx) + ((c + (d - c) * fx) - (a + (b - a) * fx)) * fy;
}

static float maps__smooth(float e0, float e1, float x)
{
    float t = (x - e0) / (e1 - e0);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return t * t * (3 - 2 * t);
}

/* Bricks: running bond, bevelled edges, mortar low and rough. */
static void maps__bricks(float u, float v, float *h, float rgb[3], float *spec)
{
    float by = v * MAPS__ROWS, row = floorf(by), fy = by - row;
    float bx = u * MAPS__COLS + (fmodf(row, 2) ? 0.5f : 0), col = floorf(bx), fx = bx - col;
    float dx = fminf(fx, 1 - fx) / MAPS__COLS, dy = fminf(fy, 1 - fy) / MAPS__ROWS;
    float d = fminf(dx, dy), n = maps__noise(u, v, MAPS__NOISE_CELLS, 7);
    float id = maps__hash((uint32_t)col % MAPS__COLS, (uint32_t)row, 3);
    float t = (d - MAPS__MORTAR) / MAPS__BEVEL;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    t = t * t * (3 - 2 * t);
    *h = 0.12f + 0.06f * n + t * (0.68f + 0.08f * id);
    float m[3] = {0.62f, 0.60f, 0.56f}, br[3] = {0.58f, 0.24f, 0.16f};
    float shade = 0.8f + 0.4f * id;
    for (int i = 0; i < 3; i++)
        rgb[i] = (m[i] + (br[i] * shade - m[i]) * t) * (0.9f + 0.2f * n);
    *spec = 0.1f + 0.25f * t;
}

/* Stones: Worley cells (one jittered point per cell), domed by the distance
 * to the cell edge F2 - F1, dark gaps between them. */
static void maps__stones(float u, float v, float *h, float rgb[3], float *spec)
{
    const int n = MAPS__STONE_CELLS;
    float x = u * (float)n, y = v * (float)n, f1 = 9, f2 = 9, id = 0;
    int cx = (int)floorf(x), cy = (int)floorf(y);
    for (int j = -1; j <= 1; j++)
        for (int i = -1; i <= 1; i++) {
            uint32_t hx = (uint32_t)((cx + i + n) % n), hy = (uint32_t)((cy + j + n) % n);
            float px = (float)(cx + i) + 0.15f + 0.7f * maps__hash(hx, hy, 21);
            float py = (float)(cy + j) + 0.15f + 0.7f * maps__hash(hx, hy, 22);
            float d = sqrtf((px - x) * (px - x) + (py - y) * (py - y));
            if (d < f1) {
                f2 = f1;
                f1 = d;
                id = maps__hash(hx, hy, 23);
            } else if (d < f2) {
                f2 = d;
            }
        }
    float edge = maps__smooth(0.02f, 0.3f, f2 - f1), nz = maps__noise(u, v, 64, 24);
    *h = 0.08f + edge * (0.62f + 0.2f * id - 0.25f * f1 * f1) + 0.05f * nz;
    float tint[3] = {0.45f + 0.15f * id, 0.42f + 0.1f * id, 0.38f};
    for (int c = 0; c < 3; c++)
        rgb[c] = (0.08f + (tint[c] - 0.08f) * edge) * (0.85f + 0.3f * nz);
    *spec = 0.05f + 0.4f * edge;
}

/* Terrain: fBm of periodic value noise, coloured by height (grass, rock, snow). */
static void maps__terrain(float u, float v, float *h, float rgb[3], float *spec)
{
    float sum = 0, amp = 1, norm = 0;
    for (int o = 0; o < MAPS__FBM_OCTAVES; o++, amp *= 0.5f) {
        sum += amp * maps__noise(u, v, 4 << o, 11 + (uint32_t)o);
        norm += amp;
    }
    float t = maps__smooth(0.2f, 0.8f, sum / norm);
    *h = t;
    float rock = maps__smooth(0.35f, 0.55f, t), snow = maps__smooth(0.7f, 0.8f, t);
    static const float grass[3] = {0.16f, 0.30f, 0.10f}, stone[3] = {0.40f, 0.33f, 0.25f},
                       ice[3] = {0.90f, 0.90f, 0.93f};
    for (int c = 0; c < 3; c++)
        rgb[c] = grass[c] + (stone[c] - grass[c]) * rock + (ice[c] - stone[c]) * snow;
    *spec = 0.04f + 0.5f * snow;
}

/* Checker: high-frequency black/white squares on a flat surface. */
static void maps__checker(float u, float v, float *h, float rgb[3], float *spec)
{
    int cx = (int)floorf(u * MAPS_CHECKER_SQUARES), cy = (int)floorf(v * MAPS_CHECKER_SQUARES);
    float a = (cx + cy) % 2 ? 0.95f : 0.05f;
    *h = 0.5f;
    rgb[0] = rgb[1] = rgb[2] = a;
    *spec = 0.5f;
}

/* Sine: separable sinusoid, analytic height and gradient. */
static void maps__sine(float u, float v, float *h, float rgb[3], float *spec)
{
    const double k = 2 * 3.14159265358979323846 * MAPS_SINE_FREQ;
    *h = (float)(0.5 + 0.25 * (sin(k * u) + sin(k * v)));
    rgb[0] = rgb[1] = rgb[2] = 0.75f;
    *spec = 0.5f;
}

static void maps__flat(float u, float v, float *h, float rgb[3], float *spec)
{
    (void)u;
    (void)v;
    *h = 0.5f;
    rgb[0] = rgb[1] = rgb[2] = 0.75f;
    *spec = 0.5f;
}

/* Asteroid: the body of mesh_asteroid_radius baked over the sphere's UVs
 * (study S4's reduced mesh): h = (r − RMIN) / (RMAX − RMIN) along the
 * direction of (u, v); grey rock, darker in the hollows. */
static void maps__asteroid(float u, float v, float *h, float rgb[3], float *spec)
{
    float d[3];
    mesh_sphere_dir(u, v, d);
    *h = (mesh_asteroid_radius(d) - MESH_ASTEROID_RMIN) / (MESH_ASTEROID_RMAX - MESH_ASTEROID_RMIN);
    float grain = maps__noise(u, v, 64, 23);
    for (int c = 0; c < 3; c++)
        rgb[c] = (0.30f + 0.03f * (float)(2 - c)) * (0.6f + 0.6f * *h) * (0.85f + 0.3f * grain);
    *spec = 0.08f;
}

#define MAPS__ASTEROID 6
static const char *const maps__names[] = {"bricks", "stones", "terrain", "checker", "sine",
                                          "flat", "asteroid", NULL};
static const maps__texel_fn maps__fns[] = {maps__bricks, maps__stones, maps__terrain,
                                           maps__checker, maps__sine, maps__flat, maps__asteroid};

/* The asteroid's normal map is not derived from its height texture: it is
 * the true normal of the body r(d)·d at each texel centre, in the sphere's
 * tangent frame T = ∂d/∂u, B = ∂d/∂v (unit), N = d, which is the frame the
 * sphere meshes get from mesh_generate_tangents.  For a radial surface
 * n ∝ d − ∇r / r with ∇r the gradient of r on the unit sphere, so in
 * tangent space n = normalize(−r_T / r, −r_B / r, 1), r_T and r_B central
 * differences of r along T and B (step 1e-3 rad) — defined at the poles. */
static void maps__asteroid_normal(float u, float v, float n[3])
{
    const float eps = 1e-3f;
    float lon = (u - 0.5f) * 6.28318531f, lat = (v - 0.5f) * 3.14159265f, d[3];
    mesh_sphere_dir(u, v, d);
    float t[3] = {cosf(lon), 0, -sinf(lon)};
    float b[3] = {-sinf(lat) * sinf(lon), cosf(lat), -sinf(lat) * cosf(lon)};
    float g[2];
    for (int k = 0; k < 2; k++) {
        const float *axis = k ? b : t;
        float p[3], m[3], lp = 0, lm = 0;
        for (int c = 0; c < 3; c++) {
            p[c] = d[c] + eps * axis[c];
            m[c] = d[c] - eps * axis[c];
            lp += p[c] * p[c];
            lm += m[c] * m[c];
        }
        for (int c = 0; c < 3; c++) {
            p[c] /= sqrtf(lp);
            m[c] /= sqrtf(lm);
        }
        g[k] = (mesh_asteroid_radius(p) - mesh_asteroid_radius(m)) / (2 * eps);
    }
    float r = mesh_asteroid_radius(d);
    float x = -g[0] / r, y = -g[1] / r, l = sqrtf(x * x + y * y + 1);
    n[0] = x / l;
    n[1] = y / l;
    n[2] = 1 / l;
}

/* Fills m->normal (allocating it) with the baked normals of the asteroid
 * set; other sets keep theirs (or none, in the compact layout). */
static void maps__bake_normals(maps_set *m, int kind)
{
    if (kind != MAPS__ASTEROID)
        return;
    size_t n = (size_t)m->size;
    if (!m->normal)
        m->normal = dm_xmalloc(n * n * 3 * sizeof(float));
    for (size_t y = 0; y < n; y++)
        for (size_t x = 0; x < n; x++)
            maps__asteroid_normal(((float)x + 0.5f) / (float)n, ((float)y + 0.5f) / (float)n,
                                  &m->normal[3 * (y * n + x)]);
}

const char *const *maps_names(void) { return maps__names; }

float maps_srgb_encode(float c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1 / 2.4f) - 0.055f;
}

float maps_srgb_decode(float c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

static uint8_t maps__unorm8(float x)
{
    x = x < 0 ? 0 : x > 1 ? 1 : x;
    return (uint8_t)lrintf(x * 255.0f);
}

void maps_normal_rows(const float *height, int size, float strength, int y0, int y1, float *normal)
{
    float s = strength * MAPS_NORMAL_SCALE * (float)size * 0.5f;
    for (int y = y0; y < y1; y++)
        for (int x = 0; x < size; x++) {
            int xm = (x + size - 1) % size, xp = (x + 1) % size;
            int ym = (y + size - 1) % size, yp = (y + 1) % size;
            float gx = s * (height[(size_t)y * (size_t)size + (size_t)xp] - height[(size_t)y * (size_t)size + (size_t)xm]);
            float gy = s * (height[(size_t)yp * (size_t)size + (size_t)x] - height[(size_t)ym * (size_t)size + (size_t)x]);
            float l = sqrtf(gx * gx + gy * gy + 1);
            float *n = &normal[3 * ((size_t)(y - y0) * (size_t)size + (size_t)x)];
            n[0] = -gx / l;
            n[1] = -gy / l;
            n[2] = 1 / l;
        }
}

void maps_normal_from_height(const float *height, int size, float strength, float *normal)
{
    maps_normal_rows(height, size, strength, 0, size, normal);
}

/* The 8-bit sRGB tables: thresholds for encoding, decoded values, and for
 * each of MAPS__SRGB_BUCKETS equal buckets of [0, 1) the count of
 * thresholds at or below its lower end. */
#define MAPS__SRGB_BUCKETS 4096
static float maps__thresh[255], maps__decoded[256];
static uint8_t maps__bucket_start[MAPS__SRGB_BUCKETS];
static pthread_once_t maps__tables_once = PTHREAD_ONCE_INIT;

static void maps__tables(void)
{
    for (int k = 0; k < 255; k++)
        maps__thresh[k] = maps_srgb_decode(((float)k + 0.5f) / 255.0f);
    for (int k = 0; k < 256; k++)
        maps__decoded[k] = maps_srgb_decode((float)k / 255.0f);
    int n = 0;
    for (int b = 0; b < MAPS__SRGB_BUCKETS; b++) {
        float lo = (float)b / MAPS__SRGB_BUCKETS;
        while (n < 255 && maps__thresh[n] <= lo)
            n++;
        maps__bucket_start[b] = (uint8_t)n;
    }
}

/* 8-bit sRGB code of a linear value: the count of the linear thresholds
 * decode((k + 0.5)/255) at or below x — no pow per texel.  The count at
 * the lower end of x's bucket, then the threshold inside the bucket, if
 * any (thresholds are 1/3295 apart at the closest, near 0; a bucket is
 * 1/4096 wide).  NaN and x <= 0 give 0, x >= 1 gives 255.  The tables
 * must be made (maps__tables). */
static inline uint8_t maps__srgb8(float x)
{
    if (!(x > 0.0f))
        return 0;
    if (x >= 1.0f)
        return 255;
    int k = maps__bucket_start[(int)(x * MAPS__SRGB_BUCKETS)];
    while (k < 255 && x >= maps__thresh[k])
        k++;
    return (uint8_t)k;
}

uint8_t maps_srgb8(float x)
{
    pthread_once(&maps__tables_once, maps__tables);
    return maps__srgb8(x);
}

void maps_texel(int kind, long size, long x, long y, float *h, float rgba[4])
{
    pthread_once(&maps__tables_once, maps__tables);
    x = ((x % size) + size) % size;
    y = ((y % size) + size) % size;
    float rgb[3], spec;
    maps__fns[kind](((float)x + 0.5f) / (float)size, ((float)y + 0.5f) / (float)size, h, rgb, &spec);
    for (int c = 0; c < 3; c++)
        rgba[c] = maps__decoded[maps__srgb8(rgb[c])];
    rgba[3] = (float)maps__unorm8(spec) / 255.0f;
}

/* Evaluates fn at every texel centre into the set's arrays. */
static void maps__fill(maps_set *m, maps__texel_fn fn, int compact)
{
    pthread_once(&maps__tables_once, maps__tables);
    size_t n = (size_t)m->size;
    for (size_t y = 0; y < n; y++)
        for (size_t x = 0; x < n; x++) {
            size_t i = y * n + x;
            float rgb[3], spec;
            fn(((float)x + 0.5f) / (float)n, ((float)y + 0.5f) / (float)n, &m->height[i], rgb, &spec);
            for (int c = 0; c < 3 && compact; c++)
                m->albedo8[4 * i + (size_t)c] = maps__srgb8(rgb[c]);
            for (int c = 0; c < 3 && !compact; c++)
                m->albedo[4 * i + (size_t)c] = rgb[c];
            if (compact) {
                m->albedo8[4 * i + 3] = maps__unorm8(spec);
            } else {
                m->albedo[4 * i + 3] = 1.0f;
                m->specular[i] = spec;
            }
        }
}

int maps_kind(const char *name)
{
    for (int i = 0; maps__names[i]; i++)
        if (strcmp(name, maps__names[i]) == 0)
            return i;
    return -1;
}

/* Allocates the arrays of a size² set in the chosen layout. */
static void maps__alloc(maps_set *m, int size, int compact)
{
    size_t texels = (size_t)size * (size_t)size;
    memset(m, 0, sizeof *m);
    m->size = size;
    m->height = dm_xmalloc(texels * sizeof(float));
    if (compact) {
        m->albedo8 = dm_xmalloc(texels * 4);
        return;
    }
    m->normal = dm_xmalloc(texels * 3 * sizeof(float));
    m->albedo = dm_xmalloc(texels * 4 * sizeof(float));
    m->specular = dm_xmalloc(texels * sizeof(float));
}

int maps_generate(const maps_desc *desc, maps_set *out)
{
    const char *name = desc && desc->name ? desc->name : "bricks";
    int size = desc && desc->size ? desc->size : 512;
    float strength = desc && desc->normal_strength != 0 ? desc->normal_strength : 1.0f;
    int compact = desc && desc->compact, kind = maps_kind(name);
    if (kind < 0)
        return DM_ERR_UNKNOWN;
    if (size < MAPS_MIN_SIZE || size > MAPS_MAX_SIZE)
        return DM_ERR_RANGE;
    int64_t t0 = dm_now_ns();
    maps__alloc(out, size, compact);
    maps__fill(out, maps__fns[kind], compact);
    if (!compact)
        maps_normal_from_height(out->height, size, strength, out->normal);
    maps__bake_normals(out, kind);
    out->gen_ns = dm_now_ns() - t0;
    return 0;
}

char *maps_cache_dir(void)
{
    const char *d = getenv("DMBENCH_CACHE_DIR"), *x = getenv("XDG_CACHE_HOME");
    if (d && *d)
        return dm_xasprintf("%s/maps", d);
    if (x && *x)
        return dm_xasprintf("%s/dmbench/maps", x);
    const char *home = getenv("HOME");
    return dm_xasprintf("%s/.cache/dmbench/maps", home && *home ? home : "/tmp");
}

/* Cache file layout: magic (8 bytes), int32 size, then size² float heights
 * and size²·4 albedo8 bytes, then a uint64 FNV-1a hash of both arrays, native
 * byte order (the cache is per machine).  A file whose hash does not match
 * (a damaged block) is not used; the maps are generated again. */
static uint64_t maps__cache_hash(const maps_set *m)
{
    size_t texels = (size_t)m->size * (size_t)m->size;
    uint64_t h = dm_fnv1a64(m->height, texels * sizeof(float), DM_FNV_SEED);
    return dm_fnv1a64(m->albedo8, texels * 4, h);
}

static int maps__cache_read(const char *path, int size, maps_set *out)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return DM_ERR_IO;
    char magic[8];
    int32_t s = 0;
    size_t texels = (size_t)size * (size_t)size;
    maps__alloc(out, size, 1);
    int ok = fread(magic, 1, 8, f) == 8 && memcmp(magic, MAPS__CACHE_MAGIC, 8) == 0 &&
             fread(&s, sizeof s, 1, f) == 1 && s == size &&
             fread(out->height, sizeof(float), texels, f) == texels &&
             fread(out->albedo8, 4, texels, f) == texels;
    uint64_t stored = 0;
    char extra;
    ok = ok && fread(&stored, sizeof stored, 1, f) == 1 && fread(&extra, 1, 1, f) == 0 &&
         stored == maps__cache_hash(out);
    fclose(f);
    if (!ok)
        maps_free(out);
    return ok ? 0 : DM_ERR_IO;
}

/* Writes through a temporary file and rename, so readers never see half a file. */
static int maps__cache_write(const char *dir, const char *path, const maps_set *m)
{
    size_t texels = (size_t)m->size * (size_t)m->size;
    int32_t s = m->size;
    char *tmp = dm_xasprintf("%s.%ld.tmp", path, (long)getpid());
    FILE *f = dm_mkdirs(dir) == 0 ? fopen(tmp, "wb") : NULL;
    int ok = f && fwrite(MAPS__CACHE_MAGIC, 1, 8, f) == 8 && fwrite(&s, sizeof s, 1, f) == 1 &&
             fwrite(m->height, sizeof(float), texels, f) == texels &&
             fwrite(m->albedo8, 4, texels, f) == texels;
    uint64_t h = maps__cache_hash(m);
    ok = ok && fwrite(&h, sizeof h, 1, f) == 1;
    if (f && fclose(f) != 0)
        ok = 0;
    if (ok && rename(tmp, path) != 0)
        ok = 0;
    if (!ok && f)
        unlink(tmp);
    free(tmp);
    return ok ? 0 : DM_ERR_IO;
}

static int maps__get_cached(const maps_desc *desc, const char *dir, maps_set *out);

/* Sets this process made or loaded, so a renderer created again (the
 * Instructions child makes one per configuration, in a fresh GL context)
 * does not generate them again: sets smaller than MAPS_CACHE_MIN_SIZE
 * (larger ones have the disk cache), up to MAPS_MEMO_SETS of them, the
 * oldest replaced first.  Prepare runs on the GL
 * thread only, so no lock. */
#define MAPS__MEMO_BYTES ((size_t)64 << 20)
static struct {
    char name[64];
    int size;
    float normal_strength;
    maps_set set;
} maps__memo[MAPS_MEMO_SETS];
static unsigned maps__memo_next;

static void *maps__dup(const void *p, size_t n)
{
    void *q = dm_xmalloc(n ? n : 1);
    memcpy(q, p, n);
    return q;
}

/* Deep copy of the arrays of src (same layout) into dst. */
static void maps__copy(const maps_set *src, maps_set *dst)
{
    size_t t = (size_t)src->size * (size_t)src->size;
    *dst = *src;
    dst->height = src->height ? maps__dup(src->height, t * sizeof(float)) : NULL;
    dst->normal = src->normal ? maps__dup(src->normal, t * 3 * sizeof(float)) : NULL;
    dst->albedo = src->albedo ? maps__dup(src->albedo, t * 4 * sizeof(float)) : NULL;
    dst->specular = src->specular ? maps__dup(src->specular, t * sizeof(float)) : NULL;
    dst->albedo8 = src->albedo8 ? maps__dup(src->albedo8, t * 4) : NULL;
}

static size_t maps__bytes(const maps_set *m)
{
    size_t t = (size_t)m->size * (size_t)m->size;
    return t * ((m->height ? 4 : 0) + (m->normal ? 12 : 0) + (m->albedo ? 16 : 0) + (m->specular ? 4 : 0) +
                (m->albedo8 ? 4 : 0));
}

static int maps__memo_find(const maps_desc *d)
{
    for (int i = 0; i < MAPS_MEMO_SETS; i++)
        if (maps__memo[i].set.size == d->size && maps__memo[i].normal_strength == d->normal_strength &&
            strcmp(maps__memo[i].name, d->name) == 0)
            return i;
    return -1;
}

static void maps__memo_put(const maps_desc *d, const maps_set *m)
{
    if (strlen(d->name) >= sizeof maps__memo[0].name || maps__bytes(m) > MAPS__MEMO_BYTES || d->size <= 0)
        return;
    unsigned i = maps__memo_next++ % MAPS_MEMO_SETS;
    maps_free(&maps__memo[i].set);
    snprintf(maps__memo[i].name, sizeof maps__memo[i].name, "%s", d->name);
    maps__memo[i].normal_strength = d->normal_strength;
    maps__copy(m, &maps__memo[i].set);
}

int maps_in_memory(const maps_desc *desc)
{
    maps_desc d = *desc;
    d.name = d.name ? d.name : "bricks";
    d.size = d.size ? d.size : 512;
    return d.size < MAPS_CACHE_MIN_SIZE && maps__memo_find(&d) >= 0;
}

int maps_get_cached(const maps_desc *desc, const char *dir, maps_set *out)
{
    maps_desc d = desc ? *desc : (maps_desc){0};
    d.compact = 1;
    d.name = d.name ? d.name : "bricks";
    d.size = d.size ? d.size : 512;
    int memo = d.size < MAPS_CACHE_MIN_SIZE ? maps__memo_find(&d) : -1;
    if (memo >= 0) {
        int64_t t0 = dm_now_ns();
        maps__copy(&maps__memo[memo].set, out);
        out->from_memory = 1;
        out->load_ns = dm_now_ns() - t0;
        return 0;
    }
    int rc = maps__get_cached(&d, dir, out);
    if (rc == 0 && d.size < MAPS_CACHE_MIN_SIZE)
        maps__memo_put(&d, out);
    return rc;
}

/* maps_get_cached without the memo: the disk cache, else generation. */
static int maps__get_cached(const maps_desc *desc, const char *dir, maps_set *out)
{
    maps_desc d = *desc;
    if (maps_kind(d.name) < 0 || d.size < MAPS_CACHE_MIN_SIZE || d.size > MAPS_MAX_SIZE)
        return maps_generate(&d, out);
    char *own = dir ? NULL : maps_cache_dir();
    const char *root = dir ? dir : own;
    char *path = dm_xasprintf("%s/%s-%d.dmmaps", root, d.name, d.size);
    int64_t t0 = dm_now_ns();
    int rc = maps__cache_read(path, d.size, out);
    if (rc == 0) {
        maps__bake_normals(out, maps_kind(d.name));
        out->load_ns = dm_now_ns() - t0;
        out->from_cache = 1;
    } else {
        rc = maps_generate(&d, out);
        if (rc == 0 && maps__cache_write(root, path, out) != 0)
            dm_log(DM_LOG_WARN, "cannot write the map cache file %s", path);
    }
    free(path);
    free(own);
    return rc;
}

void maps_free(maps_set *m)
{
    if (!m)
        return;
    free(m->height);
    free(m->normal);
    free(m->albedo);
    free(m->specular);
    free(m->albedo8);
    memset(m, 0, sizeof *m);
}

/* ---- user maps (material) ------------------------------------------------ */

static const char *const maps__material_keys[3] = {"height", "normal", "albedo"};

int maps_is_material(const char *value) { return value && strchr(value, '=') != NULL; }

/* Next entry of a material at *p: up to a single ';' (";;" stands for a ';'
 * inside a path); advances *p past it.  Returns the entry (caller frees). */
static char *maps__material_entry(const char **p)
{
    dm_str e = {0};
    dm_str_cat(&e, "");
    for (; **p; (*p)++) {
        if (**p == ';' && (*p)[1] != ';')
            break;
        dm_str_catn(&e, *p, 1);
        if (**p == ';')
            (*p)++;
    }
    if (**p == ';')
        (*p)++;
    return dm_str_take(&e);
}

/* Splits "k=PATH;k=PATH" into paths[3] (malloc'd, NULL when absent). */
static int maps__material_split(const char *value, char *paths[3], dm_str *err)
{
    int rc = 0, any = 0;
    paths[0] = paths[1] = paths[2] = NULL;
    for (const char *p = value; *p && !rc;) {
        char *t = maps__material_entry(&p);
        char *eq = strchr(t, '=');
        int k = -1;
        for (int i = 0; eq && i < 3; i++)
            if ((size_t)(eq - t) == strlen(maps__material_keys[i]) && strncmp(t, maps__material_keys[i], (size_t)(eq - t)) == 0)
                k = i;
        if (k < 0 || paths[k] || !eq[1]) {
            dm_str_printf(err, "invalid material entry '%s'; expected height=PATH, normal=PATH, albedo=PATH, each at most once, separated by ';' (write ';;' for a ';' inside a path)", t);
            rc = DM_ERR_ARG;
        } else {
            paths[k] = dm_xstrdup(eq + 1);
            any = 1;
        }
        free(t);
    }
    if (!rc && !any) {
        dm_str_printf(err, "empty material '%s'", value);
        rc = DM_ERR_ARG;
    }
    for (int i = 0; rc && i < 3; i++) {
        free(paths[i]);
        paths[i] = NULL;
    }
    return rc;
}

/* Loads one map file and checks size and values; *size set or compared. */
static int maps__material_file(int key, const char *path, int *size, img *out, dm_str *err)
{
    char why[256] = "";
    if (dm_input_file(path, why, sizeof why) == DM_ERR_ARG) {
        dm_str_printf(err, "material %s map '%s' is %s", maps__material_keys[key], path, why);
        return DM_ERR_IO;
    }
    int rc = img_load(path, out, why, sizeof why);
    if (rc != 0) {   /* NOMEM: a map the machine cannot hold (exit 4), else the user's file */
        dm_str_printf(err, "material %s map '%s' cannot be read: %s", maps__material_keys[key], path, why);
        return rc == DM_ERR_NOMEM ? rc : DM_ERR_IO;
    }
    int pow2 = out->w > 0 && (out->w & (out->w - 1)) == 0;
    const char *bad = out->w != out->h || !pow2 || out->w < MAPS_MIN_SIZE || out->w > MAPS_MAX_SIZE
                          ? "must be square with a power-of-two side in [16, 16384]"
                      : *size && out->w != *size ? "differs in size from the other maps" : NULL;
    for (size_t i = 0; !bad && i < (size_t)out->w * (size_t)out->h * 4; i++)
        if (!isfinite(out->px[i]))
            bad = "holds non-finite values (NaN or infinity)";
    if (bad) {
        dm_str_printf(err, "material %s map '%s' (%dx%d) %s", maps__material_keys[key], path, out->w, out->h, bad);
        img_free(out);
        return DM_ERR_ARG;
    }
    *size = out->w;
    return 0;
}

/* Copies a loaded file into the set's map `key` (see maps.h for the meaning). */
static void maps__material_take(maps_set *m, int key, const img *im, int srgb)
{
    size_t n = (size_t)m->size * (size_t)m->size;
    for (size_t i = 0; i < n; i++) {
        const float *p = &im->px[4 * i];
        if (key == 0)
            m->height[i] = p[0];
        for (int c = 0; c < 3 && key == 1; c++)
            m->normal[3 * i + (size_t)c] = p[c] * 2 - 1;
        for (int c = 0; c < 3 && key == 2; c++)
            m->albedo[4 * i + (size_t)c] = srgb ? maps_srgb_decode(p[c]) : p[c];
    }
}

/* Loads (out != NULL) or only validates every file of the material. */
static int maps__material(const char *value, maps_set *out, dm_str *err)
{
    char *paths[3];
    int rc = maps__material_split(value, paths, err), size = 0;
    img im[3] = {{0}};
    for (int k = 0; k < 3 && !rc; k++)
        if (paths[k])
            rc = maps__material_file(k, paths[k], &size, &im[k], err);
    if (!rc && out) {
        maps_desc d = {.name = "flat", .size = size};
        rc = maps_generate(&d, out);
        for (int k = 0; k < 3 && !rc; k++) {
            const char *ext = paths[k] ? strrchr(paths[k], '.') : NULL;
            if (im[k].px)
                maps__material_take(out, k, &im[k], !(ext && strcasecmp(ext, ".exr") == 0));
        }
        if (!rc && im[0].px && !im[1].px)
            maps_normal_from_height(out->height, size, 1.0f, out->normal);
    }
    for (int k = 0; k < 3; k++) {
        img_free(&im[k]);
        free(paths[k]);
    }
    return rc;
}

int maps_material_check(const char *value, dm_str *err) { return maps__material(value, NULL, err); }

int maps_material_paths(const char *value, char *paths[3], dm_str *err)
{
    return maps__material_split(value, paths, err);
}

int maps_material_load(const char *value, maps_set *out, dm_str *err)
{
    return maps__material(value, out, err);
}
