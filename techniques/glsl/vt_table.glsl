// vt_table.glsl — the virtual texture's page table and addressing, shared
// by the stages that sample the maps through it (vt.glsl in the fragment
// stage, tess.tes.glsl for the displacement height).  See vt.glsl for the
// two paths (VT_SOFTWARE: page caches; VT_SPARSE: the sparse maps).
uniform float u_vt_size;      // virtual texels per side at level 0
uniform float u_vt_page;      // page texels per side
uniform float u_vt_border;    // border texels on each side of a page
uniform int u_vt_per_row;     // slots per row of the cache
uniform float u_vt_phys;      // cache texels per side
uniform int u_vt_levels;      // page-table levels
layout(binding = 3) uniform usampler2D t_vt_table;

float vt_lod(vec2 dx, vec2 dy)
{
    vec2 a = dx * u_vt_size, b = dy * u_vt_size;
    return 0.5 * log2(max(max(dot(a, a), dot(b, b)), 1e-20));
}

// Page of uv at level m (pages per side halve per level).
ivec2 vt_page_of(vec2 w, int m)
{
    int pages = int(u_vt_size / u_vt_page) >> m;
    return min(ivec2(w * float(pages)), ivec2(pages - 1));
}

// Cache UV of uv at level m, through the finest resident ancestor's page.
vec2 vt_phys_uv(vec2 uv, int m)
{
    vec2 w = fract(uv);
    ivec2 pg = vt_page_of(w, m);
    uvec2 e = texelFetch(t_vt_table, pg, m).xy;
    int a = int(e.y);
    float pa = u_vt_size / u_vt_page / exp2(float(a));
    vec2 off = clamp(w * pa - vec2(pg >> (a - m)), 0.0, 1.0);
    int s = int(e.x);
    vec2 slot = vec2(s % u_vt_per_row, s / u_vt_per_row) * (u_vt_page + 2.0 * u_vt_border);
    return (slot + u_vt_border + off * u_vt_page) / u_vt_phys;
}

// VT_SPARSE: the level of the finest resident page covering uv at level m.
float vt_resident(vec2 uv, int m)
{
    return float(texelFetch(t_vt_table, vt_page_of(fract(uv), m), m).y);
}
