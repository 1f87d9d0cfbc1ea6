/* technique_list.c — the one registry of techniques.
 *
 * Adding a technique = one entry here + its GLSL under techniques/glsl/.
 * The fragment-stage techniques share surface.vert.glsl (TBN in the vertex
 * stage, light and view vectors moved to tangent space — study S1 (docs/studies.md) method 3)
 * and surface.frag.glsl, whose variants are chosen by #define:
 *   SURF_UNLIT        albedo only, no lighting
 *   SURF_NORMAL_MAP   normal from the normal map (else the surface normal,
 *                     or SURF_BUMP: from the height map by central differences)
 *   SURF_PARALLAX     1 = parallax (Kaneko / Welsh with offset_limit),
 *                     2 = steep parallax, 3 = parallax occlusion mapping
 * Parallax depth: height_scale world units = height_scale·0.5 UV units (the
 * plane spans 2 world units per UV unit); plain parallax uses
 * h' = h·scale − parallax_bias·scale (default 0.5: Kaneko's scale/2); V.z is clamped to ≥ 0.05 before any division so
 * grazing views give long but finite offsets.  steps = auto picks
 * mix(max_steps, min_steps, |V.z|).  Shadows (pom only): raytrace = 30
 * steps toward the light, hard; soft = 7 samples at 0.88..0.22 of the ray,
 * shadow = 1 − clamp(max(32·(h_i − ray_i)·(1 − t_i))).
 * Every lit technique declares roughness (Cook-Torrance only: its only_if
 * condition in axes.c lets the planner fold it under the other models) and
 * specular_map (on: specular × the albedo map's alpha, S3's specular map);
 * the displacing techniques declare displaced_normals (height: SURF_BUMP's
 * normal from the height map instead of the normal map, as S3 rebuilds
 * normals after displacement).
 * Every technique-declared ENUM axis also becomes "#define AXIS_VALUE"
 * (e.g. LIGHTING_COOK_TORRANCE, SHADOW_SOFT, TOKSVIG_ON); every INT/FLOAT
 * axis is set as uniform u_<axis> (render.c), so one program serves all
 * values of a numeric axis.
 */
#include <stddef.h>

#include "techniques/technique.h"

#define TECH__LIGHT_UNIFORMS \
    "u_model, u_view_proj, u_normal_mat, u_camera_pos, u_light_pos[8], u_light_color[8], " \
    "u_light_count, u_atten (c,l,q), u_ambient, u_shininess, u_f0, u_roughness, " \
    "u_light_radius (axes)"

static const char *const tech__axes_none[] = {NULL};
static const char *const tech__axes_phong[] = {"lighting", "light_count", "roughness", "specular_map",
                                               "attenuation", "light_radius", NULL};
static const char *const tech__axes_normal[] = {"lighting", "light_count", "roughness", "specular_map",
                                                "attenuation", "light_radius",
                                                "normal_format", "toksvig", "height_scale", NULL};
static const char *const tech__axes_bump[] = {"lighting", "light_count", "roughness", "specular_map",
                                              "attenuation", "light_radius",
                                              "height_scale", "height_format", NULL};
static const char *const tech__axes_parallax[] = {"lighting", "light_count", "roughness", "specular_map",
                                                  "attenuation", "light_radius", "parallax_bias",
                                                  "normal_format", "toksvig", "height_scale",
                                                  "height_format", "offset_limit", NULL};
static const char *const tech__axes_steep[] = {"lighting", "light_count", "roughness", "specular_map",
                                               "attenuation", "light_radius",
                                               "normal_format", "toksvig", "height_scale",
                                               "height_format", "steps", "min_steps", "max_steps",
                                               NULL};
static const char *const tech__axes_tess[] = {"lighting", "light_count", "roughness", "specular_map",
                                              "attenuation", "light_radius", "tess_inner",
                                              "tess_outer",
                                              "normal_format", "toksvig", "height_scale",
                                              "tess_level", "tess_spacing", "lod", "patch_cull",
                                              "crack_free", "tess_smooth", "displaced_normals", NULL};
static const char *const tech__axes_vdisp[] = {"lighting", "light_count", "roughness", "specular_map",
                                               "attenuation", "light_radius", "height_format",
                                               "normal_format", "toksvig", "height_scale",
                                               "vertex_filter", "visibility_test", "displaced_normals", NULL};
static const char *const tech__axes_pom[] = {"lighting", "light_count", "roughness", "specular_map",
                                             "attenuation", "light_radius",
                                             "normal_format", "toksvig", "height_scale",
                                             "height_format", "steps", "min_steps", "max_steps",
                                             "shadow", NULL};

const technique_desc technique__list[] = {
    {.name = "texture", .summary = "albedo texture only, unlit (S1 method 1)",
     .vs = "surface.vert.glsl", .fs = "surface.frag.glsl", .defines = "#define SURF_UNLIT\n",
     .textures = TECH_TEX_ALBEDO, .axes = tech__axes_none, .version = 1,
     .uniforms = "u_model, u_view_proj, u_normal_mat; t_albedo"},
    {.name = "phong", .summary = "albedo + per-pixel lighting with the surface normal (S1 method 2)",
     .vs = "surface.vert.glsl", .fs = "surface.frag.glsl", .defines = NULL,
     .textures = TECH_TEX_ALBEDO, .axes = tech__axes_phong, .version = 1,
     .uniforms = TECH__LIGHT_UNIFORMS "; t_albedo"},
    {.name = "normal", .summary = "tangent-space normal mapping, TBN in the vertex stage (S1 method 3)",
     .vs = "surface.vert.glsl", .fs = "surface.frag.glsl", .defines = "#define SURF_NORMAL_MAP\n",
     .textures = TECH_TEX_NORMAL | TECH_TEX_ALBEDO, .axes = tech__axes_normal, .version = 1,
     .uniforms = TECH__LIGHT_UNIFORMS "; t_normal, t_albedo"},
    {.name = "bump", .summary = "bump mapping: normal from the height map by central differences",
     .vs = "surface.vert.glsl", .fs = "surface.frag.glsl", .defines = "#define SURF_BUMP\n",
     .textures = TECH_TEX_HEIGHT | TECH_TEX_ALBEDO, .axes = tech__axes_bump, .version = 1,
     .uniforms = TECH__LIGHT_UNIFORMS ", u_height_scale; t_height, t_albedo"},
    {.name = "parallax", .summary = "parallax mapping (Kaneko; offset_limit on = Welsh)",
     .vs = "surface.vert.glsl", .fs = "surface.frag.glsl",
     .defines = "#define SURF_NORMAL_MAP\n#define SURF_PARALLAX 1\n",
     .textures = TECH_TEX_HEIGHT | TECH_TEX_NORMAL | TECH_TEX_ALBEDO,
     .axes = tech__axes_parallax, .version = 1,
     .uniforms = TECH__LIGHT_UNIFORMS ", u_height_scale, u_parallax_bias; t_height, t_normal, "
                 "t_albedo"},
    {.name = "steep-parallax", .summary = "steep parallax mapping: linear search of the height field",
     .vs = "surface.vert.glsl", .fs = "surface.frag.glsl",
     .defines = "#define SURF_NORMAL_MAP\n#define SURF_PARALLAX 2\n",
     .textures = TECH_TEX_HEIGHT | TECH_TEX_NORMAL | TECH_TEX_ALBEDO,
     .axes = tech__axes_steep, .version = 1,
     .uniforms = TECH__LIGHT_UNIFORMS ", u_height_scale, u_steps, u_min_steps, "
                 "u_max_steps; t_height, t_normal, t_albedo"},
    {.name = "pom", .summary = "parallax occlusion mapping, optional self-shadowing (S2 scenes 4-5)",
     .vs = "surface.vert.glsl", .fs = "surface.frag.glsl",
     .defines = "#define SURF_NORMAL_MAP\n#define SURF_PARALLAX 3\n",
     .textures = TECH_TEX_HEIGHT | TECH_TEX_NORMAL | TECH_TEX_ALBEDO,
     .axes = tech__axes_pom, .version = 1,
     .uniforms = TECH__LIGHT_UNIFORMS ", u_height_scale, u_steps, u_min_steps, "
                 "u_max_steps; t_height, t_normal, t_albedo"},
    {.name = "vertex-displacement",
     .summary = "height fetched and applied in the vertex stage of a dense mesh (S1 methods 5-9)",
     .vs = "displace.vert.glsl", .fs = "surface.frag.glsl", .defines = "#define SURF_NORMAL_MAP\n",
     .textures = TECH_TEX_HEIGHT | TECH_TEX_NORMAL | TECH_TEX_ALBEDO,
     .axes = tech__axes_vdisp, .version = 1,
     .uniforms = TECH__LIGHT_UNIFORMS ", u_height_scale; t_height, t_normal, t_albedo"},
    {.name = "tess-displacement",
     .summary = "hardware tessellation, height applied in the evaluation stage (S3, S4)",
     .vs = "tess.vert.glsl", .tcs = "tess.tcs.glsl", .tes = "tess.tes.glsl",
     .fs = "surface.frag.glsl", .defines = "#define SURF_NORMAL_MAP\n",
     .textures = TECH_TEX_HEIGHT | TECH_TEX_NORMAL | TECH_TEX_ALBEDO,
     .axes = tech__axes_tess, .version = 2,
     .uniforms = TECH__LIGHT_UNIFORMS ", u_height_scale, u_tess_level, u_tess_inner, "
                 "u_tess_outer, u_viewport; lod=cpu-per-patch: u_lod_base and the "
                 "per-patch levels at storage binding 3; lod=object-points / object-cpu: "
                 "u_lod_origin, u_lod_object_dist, u_lod_tile, u_lod_tiled; "
                 "t_height, t_normal, t_albedo"},
    {.name = "reference-mesh",
     .summary = "ground truth: mesh subdivided and displaced on the CPU, per-pixel normals from the height field",
     .vs = "displace.vert.glsl", .fs = "surface.frag.glsl",
     .defines = "#define DISPLACE_REFERENCE\n#define SURF_BUMP\n",
     .textures = TECH_TEX_HEIGHT | TECH_TEX_ALBEDO, .axes = tech__axes_bump, .version = 1,
     .uniforms = TECH__LIGHT_UNIFORMS ", u_height_scale; t_height, t_albedo", .cpu_displace = 1},
    {.name = "debug-broken-shader", .summary = "test only: a fragment shader that fails to compile",
     .vs = "surface.vert.glsl", .fs = "broken.frag.glsl", .axes = tech__axes_none, .version = 1,
     .test_only = 1, .uniforms = "none"},
};

const size_t technique__list_count = sizeof technique__list / sizeof technique__list[0];
