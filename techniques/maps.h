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

const char *const *maps_names(void);   /* NULL-terminated */
/* Returns 0, DM_ERR_UNKNOWN for an unknown set, DM_ERR_RANGE for a bad size. */
int maps_generate(const maps_desc *desc, maps_set *out);
void maps_free(maps_set *m);

#endif
