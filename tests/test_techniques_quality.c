/* test_techniques_quality.c — quality truth: every technique that reads the
 * height map draws the same surface as the reference mesh (docs/techniques.md,
 * "One surface"), so error against the reference ranks techniques the way
 * they really differ.
 *
 * Every image is compared with the real reference-mesh render of its scene
 * (2× supersampled, box-filtered down), with the SSIM of imaging/quality.h
 * and PSNR over RGB.  When a check fails, the images it compared are written
 * as PNG to TECHQ_IMG_DIR (in the build tree) and the message names them.
 * Small resolutions keep the whole file to well under a minute.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/dm_image.h"
#include "imaging/quality.h"
#include "tests/tech_fixture.h"

#define W 320
#define H 180
#define REF_SS 2

static int group_setup(void **state) { return techfix_setup(state, W, H); }

/* Writes w×h RGBA floats read back from GL (bottom row first) as
 * TECHQ_IMG_DIR/<name>.png, top row first. */
static void save_png(const char *name, const float *px, int w, int h)
{
    mkdir(TECHQ_IMG_DIR, 0755);
    img im = {0};
    if (img_alloc(&im, w, h) != 0)
        return;
    size_t row = (size_t)w * 4;
    for (int y = 0; y < h; y++)
        memcpy(im.px + (size_t)y * row, px + (size_t)(h - 1 - y) * row, row * sizeof(float));
    char path[512], e[256];
    snprintf(path, sizeof path, "%s/%s.png", TECHQ_IMG_DIR, name);
    if (img_save(&im, path, e, sizeof e) != 0)
        fprintf(stderr, "cannot write %s: %s\n", path, e);
    else
        fprintf(stderr, "wrote %s\n", path);
    img_free(&im);
}

/* The reference-mesh image of scene (axis values, no technique) at W×H:
 * rendered at REF_SS× and box-filtered down (as the runner's reference). */
static float *reference(const char *scene)
{
    char spec[512];
    snprintf(spec, sizeof spec, "technique=reference-mesh %s", scene);
    target(W * REF_SS, H * REF_SS);
    float *big = render(spec);
    target(W, H);
    img src = {W * REF_SS, H * REF_SS, big}, out = {0};
    assert_int_equal(img_downsample(&src, REF_SS, &out), 0);
    free(big);
    return out.px;
}

static double ssim_of(const float *ref, const float *px)
{
    img a = {W, H, (float *)ref}, b = {W, H, (float *)px};
    double s = NAN;
    assert_int_equal(quality_ssim(&a, &b, &s), 0);
    return s;
}

/* One technique of a ladder: its name in messages and file names, and the
 * axis values it adds to the scene. */
typedef struct rung {
    const char *name;
    const char *spec;
} rung;

/* Renders every rung of the scene, scores it against the reference into
 * ssim[], and writes them all (and the reference) when `dump` is set. */
static void score(const char *tag, const char *scene, const rung *r, size_t n, double *ssim, int dump)
{
    float *ref = reference(scene);
    char spec[512], name[256];
    for (size_t i = 0; i < n; i++) {
        snprintf(spec, sizeof spec, "%s %s", r[i].spec, scene);
        float *px = render(spec);
        ssim[i] = ssim_of(ref, px);
        if (dump) {
            snprintf(name, sizeof name, "%s-%s", tag, r[i].name);
            save_png(name, px, W, H);
        }
        free(px);
    }
    if (dump) {
        snprintf(name, sizeof name, "%s-reference", tag);
        save_png(name, ref, W, H);
    }
    free(ref);
}

/* The ladder of the literature (S2, the parallax-occlusion papers): on plane
 * and cube, bricks and stones, camera elevation 30° and 50°, height_scale
 * 0.08, camera distance 2, SSIM against the reference orders POM (64 steps)
 * ≥ steep parallax (64 steps) ≥ normal mapping ≥ texture, and POM at 64
 * steps beats POM at 8.  Before the one-surface convention the searches
 * drew a relief shifted half a height_scale off the reference's and POM
 * came last.
 * One measured exception, kept visible rather than hidden: on the *plane*
 * with `stones`, normal mapping scores below unlit texture (0.638 against
 * 0.701 at 30°, 0.648 against 0.686 at 50°).  It is a property of the
 * metric on that scene, not a bug of the normal map:
 * test_stones_exception_is_misplacement proves it.  For those two scenes
 * the test asserts the rest of the ladder and prints the pair. */
static void test_ladder(void **state)
{
    (void)state;
    static const rung r[] = {
        {"texture", "technique=texture"},
        {"normal", "technique=normal"},
        {"steep64", "technique=steep-parallax steps=64"},
        {"pom8", "technique=pom steps=8"},
        {"pom64", "technique=pom steps=64"},
    };
    enum { TEX, NRM, STEEP, POM8, POM64, N };
    static const char *const meshes[] = {"plane", "cube"}, *const maps[] = {"bricks", "stones"};
    static const int elev[] = {30, 50};
    int failed = 0;
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < 2; k++)
            for (int e = 0; e < 2; e++) {
                char scene[256], tag[128];
                snprintf(scene, sizeof scene, "mesh=%s maps=%s camera.elevation=%d height_scale=0.08 "
                         "camera.distance=2", meshes[m], maps[k], elev[e]);
                snprintf(tag, sizeof tag, "ladder-%s-%s-%d", meshes[m], maps[k], elev[e]);
                int exception = m == 0 && k == 1;   /* plane + stones: see above */
                double s[N];
                score(tag, scene, r, N, s, 0);
                int ok = s[POM64] >= s[STEEP] && s[STEEP] >= s[NRM] && s[STEEP] >= s[TEX] &&
                         (exception || s[NRM] >= s[TEX]) && s[POM64] > s[POM8];
                printf("%-24s texture %.4f  normal %.4f  steep64 %.4f  pom8 %.4f  pom64 %.4f  %s\n", tag,
                       s[TEX], s[NRM], s[STEEP], s[POM8], s[POM64],
                       !ok ? "OUT OF ORDER" : exception && s[NRM] < s[TEX] ? "ok (normal < texture: misplaced detail)" : "ok");
                if (!ok) {
                    score(tag, scene, r, N, s, 1);
                    failed++;
                }
            }
    if (failed)
        fail_msg("%d of 8 scenes do not order pom64 >= steep64 >= normal >= texture, pom64 > pom8 "
                 "(images in %s)", failed, TECHQ_IMG_DIR);
}

/* Why normal mapping scores below texture on the plane with stones at 30°
 * (test_ladder): the normal map's lighting is right and SSIM punishes the
 * detail's *position*.  Measured (320×180): texture 0.701, normal 0.638,
 * normal rgba32f 0.638, bump 0.635, parallax 0.739, POM 64 0.883.
 *  - quantisation: rgba32f normals score as rgb8 (within 0.002);
 *  - sign, scale, tangent frame: `bump` differentiates the height map in
 *    the shader, with no normal map at all, and scores as `normal`
 *    (within 0.01);
 *  - lighting right: seen from above (elevation 89°, where the relief
 *    shifts nothing) normal mapping beats texture by far (0.756 against
 *    0.593), and so it does at 30° with a quarter of the relief
 *    (height_scale 0.02: 0.947 against 0.886), where the shift is a
 *    quarter as large;
 *  - position: every technique that moves the detail to where the relief
 *    puts it (parallax, POM) beats texture at 30°.
 * From above nothing but the lighting tells normal from texture, so the
 * map's lighting matches the reference's; at 30° the same lighting is
 * drawn where the flat plane puts it, not where the relief does. */
static void test_stones_exception_is_misplacement(void **state)
{
    (void)state;
    enum { TEX, NRM, NRM32, BUMP, PAR, N };
    static const rung r[N] = {
        [TEX] = {"texture", "technique=texture"}, [NRM] = {"normal", "technique=normal"},
        [NRM32] = {"normal32f", "technique=normal normal_format=rgba32f"},
        [BUMP] = {"bump", "technique=bump"}, [PAR] = {"parallax", "technique=parallax"},
    };
    static const char *const scenes[] = {
        "mesh=plane maps=stones camera.elevation=30 height_scale=0.08 camera.distance=2",
        "mesh=plane maps=stones camera.elevation=89 height_scale=0.08 camera.distance=2",
        "mesh=plane maps=stones camera.elevation=30 height_scale=0.02 camera.distance=2",
    };
    double s[3][N];
    for (int i = 0; i < 3; i++) {
        score("stones", scenes[i], r, N, s[i], 0);
        printf("%s: texture %.4f normal %.4f normal-rgba32f %.4f bump %.4f parallax %.4f\n", scenes[i],
               s[i][TEX], s[i][NRM], s[i][NRM32], s[i][BUMP], s[i][PAR]);
    }
    int ok = s[0][NRM] < s[0][TEX] && fabs(s[0][NRM32] - s[0][NRM]) < 0.002 &&
             fabs(s[0][BUMP] - s[0][NRM]) < 0.01 && s[1][NRM] > s[1][TEX] + 0.1 &&
             s[2][NRM] > s[2][TEX] + 0.03 && s[0][PAR] > s[0][TEX];
    if (!ok)
        for (int i = 0; i < 3; i++)
            score(i == 0 ? "stones-30" : i == 1 ? "stones-89" : "stones-30-hs002", scenes[i], r, N, s[i], 1);
    assert_true(ok);
}

/* PSNR of the rung against the scene's reference (images written on request). */
static void psnr_ladder(const char *tag, const char *scene, const rung *r, size_t n, double *out, int dump)
{
    float *ref = reference(scene);
    char spec[512], name[256];
    for (size_t i = 0; i < n; i++) {
        snprintf(spec, sizeof spec, "%s %s", r[i].spec, scene);
        float *px = render(spec);
        out[i] = psnr(ref, px, npix());
        if (dump) {
            snprintf(name, sizeof name, "%s-%s", tag, r[i].name);
            save_png(name, px, W, H);
        }
        free(px);
    }
    if (dump) {
        snprintf(name, sizeof name, "%s-reference", tag);
        save_png(name, ref, W, H);
    }
    free(ref);
}

/* POM on a smooth height field (`sine`) converges to the reference mesh:
 * PSNR does not fall as steps go 8, 32, 128, 512 (PSNR_SLACK_DB of slack:
 * once converged, the layers' sample positions move the result by a few
 * hundredths of a dB either way), 512 steps gain over 1 dB on 8, and at 512 steps POM is within
 * POM_VS_TESS_DB of tessellation displacement at level 32 on a dense plane
 * (33 patches a side, about 1 000 evaluated vertices across a 320-pixel
 * view) — the two ways of drawing the same surface agree.  Measured
 * (2026-11-30, Mesa 22.3.6 llvmpipe): 44.46 dB, and 44.44 dB at level 64 on
 * 65 patches a side, which drew 16 times the vertices (38 s of the file's
 * 48 s against 2.9 s). */
#define POM_VS_TESS_DB 3.0
#define PSNR_SLACK_DB 0.1
static void test_pom_converges_to_reference(void **state)
{
    (void)state;
    static const rung r[] = {
        {"pom8", "technique=pom steps=8"},
        {"pom32", "technique=pom steps=32"},
        {"pom128", "technique=pom steps=128"},
        {"pom512", "technique=pom steps=512"},
        {"tess32", "technique=tess-displacement tess_level=32 mesh_density=33"},
    };
    /* Close and narrow (fov 20°) so that the view holds only relief: no
     * plane edge, whose displaced silhouette no parallax method can draw. */
    const char *scene = "mesh=plane maps=sine camera.elevation=20 height_scale=0.12 camera.distance=0.7 "
                        "camera.fov=20";
    double p[5];
    psnr_ladder("converge", scene, r, 5, p, 0);
    printf("pom on sine: steps 8 %.2f dB, 32 %.2f, 128 %.2f, 512 %.2f; tess 32 %.2f dB\n", p[0], p[1],
           p[2], p[3], p[4]);
    int ok = p[1] >= p[0] - PSNR_SLACK_DB && p[2] >= p[1] - PSNR_SLACK_DB && p[3] >= p[2] - PSNR_SLACK_DB &&
             p[3] > p[0] + 1.0 && fabs(p[3] - p[4]) <= POM_VS_TESS_DB;
    if (!ok) {
        psnr_ladder("converge", scene, r, 5, p, 1);
        fail_msg("pom does not converge to the reference: 8 %.2f, 32 %.2f, 128 %.2f, 512 %.2f dB, "
                 "tess 32 %.2f dB (images in %s)", p[0], p[1], p[2], p[3], p[4], TECHQ_IMG_DIR);
    }
}

/* Tessellation displacement at level 64 on the plane is closer to the
 * reference than at level 1 (which is the flat plane), in PSNR and SSIM. */
static void test_tess_level_approaches_reference(void **state)
{
    (void)state;
    static const rung r[] = {
        {"tess1", "technique=tess-displacement tess_level=1"},
        {"tess64", "technique=tess-displacement tess_level=64"},
    };
    const char *scene = "mesh=plane maps=bricks camera.elevation=30 height_scale=0.08";
    double p[2], s[2];
    psnr_ladder("tess", scene, r, 2, p, 0);
    score("tess", scene, r, 2, s, 0);
    printf("tess on plane: level 1 %.2f dB SSIM %.4f; level 64 %.2f dB SSIM %.4f\n", p[0], s[0], p[1], s[1]);
    if (!(p[1] > p[0] + 1.0 && s[1] > s[0])) {
        psnr_ladder("tess", scene, r, 2, p, 1);
        fail_msg("tess level 64 (%.2f dB, SSIM %.4f) is not closer to the reference than level 1 "
                 "(%.2f dB, SSIM %.4f); images in %s", p[1], s[1], p[0], s[0], TECHQ_IMG_DIR);
    }
}

/* Largest |difference| of RGB over the pixels either image covers. */
static double max_diff(const float *a, const float *b)
{
    double m = 0;
    for (size_t i = 0; i < npix(); i++)
        for (int c = 0; c < 3; c++)
            m = fmax(m, fabs((double)a[4 * i + (size_t)c] - (double)b[4 * i + (size_t)c]));
    return m;
}

/* Normal maps follow height_scale: the procedural normal map is derived for
 * height_scale 0.06, and the shader scales its x, y by height_scale/0.06
 * before normalising, which is exact for a normal derived from a height
 * field.  So on a lit plane (smooth `sine`, magnified: no mip filtering
 * in the way) `normal` shades like `bump` at 0.03, 0.06 and 0.12 — within
 * NORMAL_VS_BUMP of each other with float maps (what remains is the
 * bilinear filtering of normals against that of heights), and within
 * NORMAL_VS_BUMP_RGB8 · height_scale/0.06 with the default 8-bit map: its
 * quantisation (half a step of 1/127.5 in x and y, through an exponent-48
 * highlight) grows with the factor that scales x and y.  A map that
 * ignored height_scale is off by far more at 0.03 and 0.12 (checked, so
 * the test can fail).  Measured: 0.0003 / 0.0010 / 0.0046 with rgba32f,
 * 0.024 / 0.047 / 0.089 with rgb8, 0.61 / 0.001 / 0.93 unscaled. */
#define NORMAL_VS_BUMP 0.01
#define NORMAL_VS_BUMP_RGB8 0.06
static void test_normal_map_follows_height_scale(void **state)
{
    (void)state;
    static const char *const hs[] = {"0.03", "0.06", "0.12"};
    const char *scene = "mesh=plane maps=sine texture_size=256 camera.distance=1.2 camera.elevation=60 "
                        "height_format=r32f";
    char spec[512];
    for (int i = 0; i < 3; i++) {
        double lim8 = NORMAL_VS_BUMP_RGB8 * atof(hs[i]) / 0.06;
        snprintf(spec, sizeof spec, "technique=bump height_scale=%s %s", hs[i], scene);
        float *bump = render(spec);
        snprintf(spec, sizeof spec, "technique=normal normal_format=rgba32f height_scale=%s %s", hs[i], scene);
        float *nf = render(spec);
        snprintf(spec, sizeof spec, "technique=normal normal_format=rgb8 height_scale=%s %s", hs[i], scene);
        float *n8 = render(spec);
        snprintf(spec, sizeof spec, "technique=normal normal_format=rgba32f height_scale=0.06 %s", scene);
        float *fixed = render(spec);
        double df = max_diff(bump, nf), d8 = max_diff(bump, n8), dfix = max_diff(bump, fixed);
        printf("height_scale %s: |normal - bump| max %.4f (rgba32f), %.4f (rgb8); map made for 0.06: %.4f\n",
               hs[i], df, d8, dfix);
        char name[64];
        if (df > NORMAL_VS_BUMP || d8 > lim8 || (i != 1 && dfix < 10 * NORMAL_VS_BUMP)) {
            snprintf(name, sizeof name, "normal-hs%s-bump", hs[i]);
            save_png(name, bump, W, H);
            snprintf(name, sizeof name, "normal-hs%s-rgba32f", hs[i]);
            save_png(name, nf, W, H);
            snprintf(name, sizeof name, "normal-hs%s-rgb8", hs[i]);
            save_png(name, n8, W, H);
            fail_msg("height_scale %s: normal against bump %.4f (rgba32f, limit %.2f), %.4f (rgb8, limit "
                     "%.3f), unscaled map %.4f; images in %s", hs[i], df, NORMAL_VS_BUMP, d8,
                     lim8, dfix, TECHQ_IMG_DIR);
        }
        free(bump);
        free(nf);
        free(n8);
        free(fixed);
    }
}

/* Coverage mask (alpha > 0.5) of an image and its crack pixels. */
static long crack_pixels(const float *px, int w, int h)
{
    img im = {w, h, (float *)px};
    unsigned char *mask = malloc((size_t)w * (size_t)h);
    quality_coverage(&im, mask);
    long n = quality_crack_pixels(mask, w, h);
    free(mask);
    return n;
}

/* vertex_filter mip on a dense plane at 15° elevation: no background pixel
 * inside the surface.  llvmpipe answers textureSize(sampler, lod) with one
 * lane's lod for a whole 8-vertex batch, so where `mip` switched level
 * between neighbouring vertices, a vertex shaded in two batches got two
 * heights: a row of holes across the plane (118 pixels at 960×540 before
 * the fix).  mip-lerp and the 30° view must stay clean too. */
static void test_vertex_mip_no_holes(void **state)
{
    (void)state;
    static const char *const specs[] = {
        "vertex_filter=mip camera.elevation=15",
        "vertex_filter=mip-lerp camera.elevation=15",
        "vertex_filter=mip camera.elevation=30",
    };
    target(960, 540);
    for (int i = 0; i < 3; i++) {
        char spec[256];
        snprintf(spec, sizeof spec, "technique=vertex-displacement mesh=plane mesh_density=1024 "
                 "camera.distance=1.6 %s", specs[i]);
        float *px = render(spec);
        long cracks = crack_pixels(px, 960, 540);
        printf("%s: %ld crack pixels\n", specs[i], cracks);
        if (cracks != 0) {
            save_png("vertex-mip-holes", px, 960, 540);
            free(px);
            target(W, H);
            fail_msg("%s: %ld background pixels inside the surface (image in %s)", specs[i], cracks,
                     TECHQ_IMG_DIR);
        }
        free(px);
    }
    target(W, H);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ladder),
        cmocka_unit_test(test_pom_converges_to_reference),
        cmocka_unit_test(test_tess_level_approaches_reference),
        cmocka_unit_test(test_normal_map_follows_height_scale),
        cmocka_unit_test(test_stones_exception_is_misplacement),
        cmocka_unit_test(test_vertex_mip_no_holes),
    };
    return cmocka_run_group_tests(tests, group_setup, teardown);
}
