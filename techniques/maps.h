/* maps.h — procedural material maps (height, normal, albedo).
 *
 * Maps are square float images generated on the CPU, row 0 = v 0.  Height is
 * one channel in [0,1]; the normal map is tangent-space, stored as unit
 * vectors in [-1,1]^3 (z up, out of the surface); albedo is linear RGBA.
 * The normal map is derived from the height map by central differences with
 * a stated strength, so the two agree.
 */
#ifndef TECHNIQUES_MAPS_H
#define TECHNIQUES_MAPS_H

#include <stddef.h>

typedef struct maps_desc {
    const char *name;       /* "bricks" (default), "flat" (height 0.5, normal +Z) */
    int size;               /* texels per side; 0 = 512 */
    float normal_strength;  /* 0 = 1.0: scale of height gradients into the normal */
} maps_desc;

typedef struct maps_set {
    int size;
    float *height;          /* size*size */
    float *normal;          /* size*size*3 */
    float *albedo;          /* size*size*4 */
} maps_set;

/* Texel counts per side accepted by maps_generate. */
#define MAPS_MIN_SIZE 16
#define MAPS_MAX_SIZE 16384
/* Gradient scale at normal_strength 1: the default height_scale 0.06 spread
 * over the 2 world units that the UV range 0..1 spans on the built-in plane,
 * so the normal map matches the displaced surface of the default scene. */
#define MAPS_NORMAL_SCALE 0.03f

const char *const *maps_names(void);   /* NULL-terminated */
/* Returns 0, DM_ERR_UNKNOWN for an unknown set, DM_ERR_RANGE for a bad size. */
int maps_generate(const maps_desc *desc, maps_set *out);
void maps_free(maps_set *m);
/* Normal map from a size×size height map by central differences with
 * wrap-around (maps tile):  g_u = (h[x+1] - h[x-1]) * size/2 is ∂h/∂u per
 * unit of UV (likewise g_v along rows), s = strength * MAPS_NORMAL_SCALE and
 * n = normalize(-s*g_u, -s*g_v, 1).  normal gets size*size*3 floats. */
void maps_normal_from_height(const float *height, int size, float strength, float *normal);

#endif
