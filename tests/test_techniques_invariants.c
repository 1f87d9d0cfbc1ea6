/* Numerical stability and invariants of the fragment-stage techniques
 * (Techniques I): the extreme-case matrix, POM convergence, the flat normal
 * map against phong, and ray-traced self-shadowing that only darkens. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tests/tech_fixture.h"
#include "techniques/technique.h"

static int setup(void **state) { return techfix_setup(state, 160, 90); }

static double mean_luma(const float *px, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++)
        s += 0.2126 * px[4 * i] + 0.7152 * px[4 * i + 1] + 0.0722 * px[4 * i + 2];
    return s / (double)n;
}

/* Every lit technique at grazing and top-down views, with height_scale 0,
 * default, 10x default and negative, steps 1 and 256, and 8 lights: the float
 * render has no non-finite pixel and none outside [0, 1e4]. */
static void test_extreme_matrix(void **state)
{
    (void)state;
    static const char *const scales[] = {"0", "0.06", "0.6", "-0.06"};
    static const char *const steps[] = {"1", "256"};
    size_t renders = 0;
    for (size_t t = 0; t < technique_count(); t++) {
        const technique_desc *d = technique_at(t);
        if (d->test_only || d->cpu_displace)
            continue;
        int hs = technique_reads_axis(d, "height_scale"), st = technique_reads_axis(d, "steps");
        int lc = technique_reads_axis(d, "light_count");
        for (int e = 0; e < 2; e++)
            for (size_t s = 0; s < (hs ? 4u : 1u); s++)
                for (size_t k = 0; k < (st ? 2u : 1u); k++) {
                    char spec[256];
                    snprintf(spec, sizeof spec, "technique=%s mesh=plane camera.elevation=%s%s%s%s%s%s",
                             d->name, e ? "89" : "1", hs ? " height_scale=" : "", hs ? scales[s] : "",
                             st ? " steps=" : "", st ? steps[k] : "", lc ? " light_count=8" : "");
                    render_expect_in_range(spec);
                    renders++;
                }
    }
    assert_true(renders >= 40);
}

/* POM converges: 256 and 512 steps agree (>= 45 dB); 8 steps is clearly
 * further from 512 than 256 is. */
static void test_pom_converges(void **state)
{
    (void)state;
    const char *base = "technique=pom mesh=plane height_scale=0.12 camera.elevation=25 camera.distance=1.6";
    char spec[256];
    float *img[3];
    static const char *const n[3] = {"8", "256", "512"};
    for (int i = 0; i < 3; i++) {
        snprintf(spec, sizeof spec, "%s steps=%s", base, n[i]);
        img[i] = render(spec);
    }
    double p256 = psnr(img[1], img[2], npix()), p8 = psnr(img[0], img[2], npix());
    if (!(p256 >= 45.0) || !(p8 < p256 - 5.0))
        fail_msg("pom 256 vs 512: %.1f dB; 8 vs 512: %.1f dB", p256, p8);
    for (int i = 0; i < 3; i++)
        free(img[i]);
}

/* normal mapping with a flat normal map equals phong (>= 60 dB). */
static void test_flat_normal_map_is_phong(void **state)
{
    (void)state;
    float *a = render("technique=normal mesh=plane maps=flat");
    float *b = render("technique=phong mesh=plane maps=flat");
    double p = psnr(a, b, npix());
    if (!(p >= 60.0))
        fail_msg("normal with a flat map vs phong: %.1f dB", p);
    free(a);
    free(b);
}

/* Ray-traced self-shadowing darkens a bumpy surface lit at a grazing angle
 * and never brightens any pixel; without shadows nothing changes. */
static void test_raytrace_shadow_darkens(void **state)
{
    (void)state;
    const char *base = "technique=pom mesh=plane height_scale=0.15 camera.distance=1.2 camera.elevation=10";
    char spec[256];
    snprintf(spec, sizeof spec, "%s shadow=none", base);
    float *none = render(spec);
    float *again = render(spec);
    snprintf(spec, sizeof spec, "%s shadow=raytrace", base);
    float *ray = render(spec);
    assert_true(isinf(psnr(none, again, npix())));
    double dn = mean_luma(none, npix()), dr = mean_luma(ray, npix());
    size_t brighter = 0, darker = 0;
    for (size_t i = 0; i < npix() * 4; i++) {
        if (i % 4 == 3)
            continue;
        brighter += ray[i] > none[i] + 1e-5f;
        darker += ray[i] < none[i] - 1e-3f;
    }
    if (!(dr < dn) || brighter != 0 || darker < 50)
        fail_msg("mean luma none %.4f raytrace %.4f; %zu values brighter, %zu darker", dn, dr,
                 brighter, darker);
    free(none);
    free(again);
    free(ray);
}

DM_TEST_MAIN(setup, teardown,
             cmocka_unit_test(test_extreme_matrix),
             cmocka_unit_test(test_pom_converges),
             cmocka_unit_test(test_flat_normal_map_is_phong),
             cmocka_unit_test(test_raytrace_shadow_darkens))
