/* technique.h — technique descriptors and their registry.
 *
 * A technique is data plus shaders: this descriptor names its GLSL stages
 * (files under techniques/glsl/, embedded at build time), its defines, the
 * textures it samples and the sweep axes it reads beyond the scene axes.
 * Adding a technique = one descriptor in technique_list.c + its GLSL.
 */
#ifndef TECHNIQUES_TECHNIQUE_H
#define TECHNIQUES_TECHNIQUE_H

#include <stddef.h>
#include <stdint.h>

enum technique_texture {
    TECH_TEX_HEIGHT = 1u << 0,
    TECH_TEX_NORMAL = 1u << 1,
    TECH_TEX_ALBEDO = 1u << 2
};

typedef struct technique_desc {
    const char *name;            /* sweep value, e.g. "normal" */
    const char *summary;         /* one line for `dmbench list techniques` */
    const char *vs, *tcs, *tes, *gs, *fs;   /* embedded GLSL names; NULL = stage absent */
    const char *defines;         /* extra "#define ..." lines, may be NULL */
    unsigned textures;           /* TECH_TEX_* bits */
    const char *const *axes;     /* technique-specific axes it reads, NULL-terminated */
    int version;                 /* bump when the technique's output changes (config keys) */
    const char *requires_ext;    /* GL extension needed, NULL if none */
    int test_only;               /* 1: hidden from the `technique` axis and listings (tests only) */
    const char *uniforms;        /* documentation: the uniforms/params its shaders read */
    int cpu_displace;            /* 1: the renderer subdivides the mesh to about 2^20
                                    triangles and displaces it on the CPU from the
                                    height map (reference-mesh; render.c) */
    uint64_t source_hash;        /* user techniques: FNV-1a of the user's file, part of
                                    the configuration key (user_technique.h); 0 built-in */
} technique_desc;

/* The catalog's lookups (catalog.h, catalog.c).
 * All registered techniques, test-only ones included (check test_only):
 * the built-in list, then the user techniques loaded so far
 * (user_technique.h). */
size_t technique_count(void);
const technique_desc *technique_at(size_t i);
const technique_desc *technique_find(const char *name);
/* Names of the techniques a user may choose (test_only == 0),
 * NULL-terminated, in registry order. */
const char *const *technique_names(void);
/* 1 when the technique reads axis `name` (its own list or a scene axis). */
int technique_reads_axis(const technique_desc *t, const char *name);

#endif
