/* Lights, camera target, roughness and the normals view (Techniques I
 * extreme cases; viewer L/N/pan support): a light exactly on the surface,
 * the Cook-Torrance mirror lobe as roughness -> 0, the light.* and
 * camera.target_* scene axes, and the normals debug view. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "tests/tech_fixture.h"
#include "techniques/technique.h"

#define W 320
#define H 180
#define DEG (3.14159265358979323846 / 180.0)

static int setup(void **state) { return techfix_setup(state, W, H); }

static double luma(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

/* Every technique of the registry (but the 2^20-triangle reference mesh)
 * with a light exactly on the surface: light.distance 0 (every light at the
 * camera target, the origin, on the plane) and light.elevation -20 (light 0
 * in the plane y = 0 at the default camera elevation 20), 1 and 8 lights,
 * every lighting model and Cook-Torrance at the smallest roughness. */
static void test_light_on_surface(void **state)
{
    (void)state;
    target(96, 54);
    static const char *const place[] = {"light.distance=0", "light.elevation=-20"};
    static const char *const model[] = {"lighting=lambert", "lighting=phong",
                                        "lighting=blinn-phong", "lighting=cook-torrance",
                                        "lighting=cook-torrance roughness=0.01"};
    size_t renders = 0;
    for (size_t t = 0; t < technique_count(); t++) {
        const technique_desc *d = technique_at(t);
        if (d->test_only || d->cpu_displace)
            continue;
        int lit = technique_reads_axis(d, "lighting");
        for (size_t p = 0; p < 2; p++)
            for (int lc = 1; lc <= 8; lc += 7)
                for (size_t m = 0; m < (lit ? 5u : 1u); m++) {
                    char spec[256];
                    snprintf(spec, sizeof spec, "technique=%s mesh=plane %s light_count=%d %s",
                             d->name, place[p], lc, lit ? model[m] : "");
                    render_expect_in_range(spec);
                    renders++;
                }
    }
    printf("light on the surface: %zu renders, none non-finite or outside [0, 1e4]\n", renders);
    assert_true(renders >= 100);
    target(W, H);
}

/* ---- the mirror lobe ---------------------------------------------------- */

/* The scene of the mirror-lobe test: default camera (distance 3, azimuth 30,
 * fov 45) at elevation 30; light 0 nearly opposite (azimuth 30 + 160) at
 * elevation 30 + 10 = 40 and distance 1.0 x 3. */
#define LOBE_SCENE "technique=phong mesh=plane maps=flat light_count=1 camera.elevation=30 " \
                   "light.azimuth=160 light.elevation=10 light.distance=1"

static void orbit(double d, double az, double el, double out[3])
{
    out[0] = d * cos(el * DEG) * sin(az * DEG);
    out[1] = d * sin(el * DEG);
    out[2] = d * cos(el * DEG) * cos(az * DEG);
}

static void sub(const double a[3], const double b[3], double o[3])
{
    for (int k = 0; k < 3; k++)
        o[k] = a[k] - b[k];
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void unit(double v[3])
{
    double l = sqrt(dot(v, v));
    for (int k = 0; k < 3; k++)
        v[k] /= l;
}

/* Camera frame: forward f, right r, up u of a camera at eye looking at tgt
 * with up +Y. */
static void camera_basis(const double eye[3], const double tgt[3], double f[3], double r[3],
                         double u[3])
{
    sub(tgt, eye, f);
    unit(f);
    r[0] = -f[2];                          /* f x (0,1,0) */
    r[1] = 0;
    r[2] = f[0];
    unit(r);
    u[0] = r[1] * f[2] - r[2] * f[1];      /* r x f */
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
}

/* Pixel (x, y from the bottom row, pixel centres at integers) of world
 * point p seen by a camera at eye looking at tgt with vertical fov (deg):
 * a pinhole projection built here from the axis values. */
static void project(const double eye[3], const double tgt[3], double fov, const double p[3],
                    double *x, double *y)
{
    double f[3], r[3], u[3], q[3];
    camera_basis(eye, tgt, f, r, u);
    sub(p, eye, q);
    double t = tan(fov * DEG / 2), z = dot(q, f);
    double nx = dot(q, r) / (z * t * ((double)W / H)), ny = dot(q, u) / (z * t);
    *x = (nx + 1) / 2 * W - 0.5;
    *y = (ny + 1) / 2 * H - 0.5;
}

/* Eye and light 0 of the lobe scene (the camera looks at the origin). */
static void lobe_scene(double eye[3], double light[3])
{
    orbit(3.0, 30, 30, eye);
    orbit(3.0 * 1.0, 30 + 160, 30 + 10, light);
}

/* The analytic mirror point of the lobe scene: the light mirrored in y = 0,
 * the segment eye -> mirrored light cut with y = 0; p in world, (x, y) in
 * pixels. */
static void mirror_point(double p[3], double *x, double *y)
{
    double eye[3], light[3], o[3] = {0, 0, 0};
    lobe_scene(eye, light);
    light[1] = -light[1];
    double t = eye[1] / (eye[1] - light[1]);
    for (int k = 0; k < 3; k++)
        p[k] = eye[k] + t * (light[k] - eye[k]);
    project(eye, o, 45, p, x, y);
}

/* Half vector (unit) of the plane point seen through pixel (x, y). */
static void half_at_pixel(double x, double y, double h[3])
{
    double eye[3], light[3], o[3] = {0, 0, 0}, f[3], r[3], u[3], d[3], p[3], l[3], v[3];
    lobe_scene(eye, light);
    camera_basis(eye, o, f, r, u);
    double t = tan(45 * DEG / 2);
    double nx = (2 * (x + 0.5) / W - 1) * t * ((double)W / H), ny = (2 * (y + 0.5) / H - 1) * t;
    for (int k = 0; k < 3; k++)
        d[k] = f[k] + nx * r[k] + ny * u[k];
    for (int k = 0; k < 3; k++)
        p[k] = eye[k] - eye[1] / d[1] * d[k];
    sub(light, p, l);
    sub(eye, p, v);
    unit(l);
    unit(v);
    for (int k = 0; k < 3; k++)
        h[k] = l[k] + v[k];
    unit(h);
}

/* The summed specular a mirror-like lobe tends to (roughness -> 0).  The
 * Beckmann D is normalised, integral of D (N.H) over half-vector directions
 * = 1, so summed over the pixels around the mirror point it tends to
 * J = pixels per steradian of H there; the rest of the specular term is
 * smooth and taken at the mirror point P, where H = N, N.H = 1,
 * V.H = N.V, G = min(1, 2 N.V / V.H) = 1:
 *   sum -> 1.6 (light colour) x att(|L - P|) x F(N.V) / (4 N.V) x J. */
static double lobe_limit(void)
{
    double p[3], mx, my, eye[3], light[3], v[3], lp[3], hx0[3], hx1[3], hy0[3], hy1[3], c[3];
    mirror_point(p, &mx, &my);
    lobe_scene(eye, light);
    half_at_pixel(mx - 0.5, my, hx0);
    half_at_pixel(mx + 0.5, my, hx1);
    half_at_pixel(mx, my - 0.5, hy0);
    half_at_pixel(mx, my + 0.5, hy1);
    sub(hx1, hx0, hx1);
    sub(hy1, hy0, hy1);
    c[0] = hx1[1] * hy1[2] - hx1[2] * hy1[1];
    c[1] = hx1[2] * hy1[0] - hx1[0] * hy1[2];
    c[2] = hx1[0] * hy1[1] - hx1[1] * hy1[0];
    double J = 1.0 / sqrt(dot(c, c));
    sub(eye, p, v);
    sub(light, p, lp);
    double nv = v[1] / sqrt(dot(v, v)), dl = sqrt(dot(lp, lp));
    double att = 1.0 / (1.0 + 0.1 * dl + 0.05 * dl * dl);
    double fres = 0.04 + 0.96 * pow(1.0 - nv, 5.0);
    return 1.6 * att * fres / (4.0 * nv) * J;
}

typedef struct lobe {
    double peak, px, py, sum;    /* brightest specular value, its pixel, summed specular */
    size_t area;                 /* pixels above half the peak */
} lobe;

/* Specular part of the Cook-Torrance render at roughness m: the render
 * minus the Lambert render of the same scene (identical diffuse and ambient). */
static lobe lobe_at(const char *m)
{
    char spec[512];
    snprintf(spec, sizeof spec, "%s lighting=cook-torrance roughness=%s", LOBE_SCENE, m);
    float *ct = render(spec);
    float *lam = render(LOBE_SCENE " lighting=lambert");
    assert_int_equal(out_of_range(ct, npix()), 0);
    lobe l = {0};
    for (size_t i = 0; i < npix(); i++) {
        double s = luma(ct + 4 * i) - luma(lam + 4 * i);
        l.sum += s;
        if (s > l.peak) {
            l.peak = s;
            l.px = (double)(i % W);
            l.py = (double)(i / W);
        }
    }
    for (size_t i = 0; i < npix(); i++)
        l.area += luma(ct + 4 * i) - luma(lam + 4 * i) > 0.5 * l.peak;
    free(ct);
    free(lam);
    return l;
}

/* Cook-Torrance with roughness -> 0 approaches a mirror lobe: the brightest
 * specular pixel moves to the analytic mirror point (within 2 px at 0.01),
 * the highlight (pixels above half the peak) shrinks and the peak rises at
 * every step, the peak stays finite and <= 1e4, and the energy is bounded:
 * the summed specular never exceeds LOBE_BOUND x the normalised-lobe limit
 * (lobe_limit) and is within LOBE_CONVERGED of it at 0.01. */
#define LOBE_BOUND 1.05
#define LOBE_CONVERGED 0.02
static void test_mirror_lobe(void **state)
{
    (void)state;
    static const char *const m[] = {"0.35", "0.1", "0.03", "0.01"};
    double p[3], mx, my, dist[4], limit = lobe_limit();
    mirror_point(p, &mx, &my);
    lobe l[4];
    for (int i = 0; i < 4; i++) {
        l[i] = lobe_at(m[i]);
        dist[i] = hypot(l[i].px - mx, l[i].py - my);
        printf("roughness %-4s: peak %.3f at (%.0f, %.0f), %.2f px from the mirror point "
               "(%.2f, %.2f); %zu px above half; sum %.2f = %.3f x the limit %.2f\n",
               m[i], l[i].peak, l[i].px, l[i].py, dist[i], mx, my, l[i].area, l[i].sum,
               l[i].sum / limit, limit);
        assert_true(isfinite(l[i].peak) && l[i].peak <= 1e4);
        assert_true(l[i].sum <= LOBE_BOUND * limit);
    }
    assert_true(mx > 0 && mx < W && my > 0 && my < H);
    for (int i = 1; i < 4; i++) {
        assert_true(dist[i] <= dist[i - 1] + 0.5);
        assert_true(l[i].area < l[i - 1].area);
        assert_true(l[i].peak > l[i - 1].peak);
    }
    assert_true(dist[3] <= 2.0);
    assert_true(dist[0] > dist[3]);
    assert_true(fabs(l[3].sum / limit - 1.0) <= LOBE_CONVERGED);
}

/* ---- light and camera-target axes --------------------------------------- */

/* Defaults render bit-identically to their explicit spelling;
 * light.azimuth moves the light. */
static void test_light_axes(void **state)
{
    (void)state;
    const char *base = "technique=pom mesh=plane light_count=3";
    char spec[512];
    float *a = render(base);
    snprintf(spec, sizeof spec, "%s light.azimuth=45 light.elevation=35 light.distance=1.2 "
             "camera.target_x=0 camera.target_y=0 camera.target_z=0 roughness=0.35", base);
    float *b = render(spec);
    assert_memory_equal(a, b, npix() * 4 * sizeof(float));
    snprintf(spec, sizeof spec, "%s light.azimuth=135", base);
    float *c = render(spec);
    double p = psnr(a, c, npix());
    printf("light.azimuth 45 vs 135: %.1f dB\n", p);
    assert_true(p < 30.0);
    free(a);
    free(b);
    free(c);
}

/* Mean x and y of the covered pixels (alpha > 0). */
static void coverage_centroid(const float *px, double *x, double *y)
{
    double sx = 0, sy = 0, n = 0;
    for (size_t i = 0; i < npix(); i++)
        if (px[4 * i + 3] > 0) {
            sx += (double)(i % W);
            sy += (double)(i / W);
            n++;
        }
    assert_true(n > 0);
    *x = sx / n;
    *y = sy / n;
}

/* camera.target_x pans: the camera and its target move together by +0.25 in
 * x, so the plane moves on screen by the projection of -0.25 x: to the left
 * (the screen right vector at azimuth 30 is (cos 30, 0, -sin 30)). */
static void test_camera_target_pans(void **state)
{
    (void)state;
    float *a = render("technique=texture mesh=plane");
    float *b = render("technique=texture mesh=plane camera.target_x=0.25");
    double ax, ay, bx, by, ox, oy, o[3] = {0, 0, 0}, eye[3], tgt[3] = {0.25, 0, 0};
    coverage_centroid(a, &ax, &ay);
    coverage_centroid(b, &bx, &by);
    orbit(3.0, 30, 20, eye);
    eye[0] += 0.25;
    project(eye, tgt, 45, o, &ox, &oy);    /* where the world origin lands after the pan */
    double want = ox - (W - 1) / 2.0;
    printf("pan 0.25: plane centroid x %.2f -> %.2f (%.2f px); origin moves %.2f px\n", ax, bx,
           bx - ax, want);
    assert_true(want < -10.0);
    assert_true(bx - ax < 0.5 * want && bx - ax > 1.5 * want);
    assert_true(fabs(by - ay) < 0.5 * fabs(bx - ax));
    free(a);
    free(b);
}

/* ---- the normals view ----------------------------------------------------- */

/* Covered pixels whose colour differs from (r, g, b) by more than tol. */
static size_t off_colour(const float *px, double r, double g, double b, double tol, size_t *cov)
{
    size_t bad = 0;
    *cov = 0;
    for (size_t i = 0; i < npix(); i++) {
        const float *p = px + 4 * i;
        if (p[3] <= 0)
            continue;
        (*cov)++;
        bad += fabs(p[0] - r) > tol || fabs(p[1] - g) > tol || fabs(p[2] - b) > tol;
    }
    return bad;
}

/* A flat plane in the normals view is (0.5, 1, 0.5) +- 1/255 everywhere it
 * covers, with phong and with normal on the flat map; every technique's
 * covered pixels decode to unit normals (+-0.01) facing up on the bricks. */
static void test_normals_view(void **state)
{
    (void)state;
    assert_int_equal(render_set_debug_view(F.r, (render_debug_view)7), DM_ERR_ARG);
    assert_int_equal(render_set_debug_view(F.r, RENDER_DEBUG_NORMALS), 0);
    static const char *const flat[] = {"technique=phong mesh=plane maps=flat",
                                       "technique=normal mesh=plane maps=flat"};
    for (int i = 0; i < 2; i++) {
        float *px = render(flat[i]);
        size_t cov, bad = off_colour(px, 0.5, 1.0, 0.5, 1.0 / 255, &cov);
        printf("normals view, %s: %zu covered px, %zu off (0.5, 1, 0.5)\n", flat[i], cov, bad);
        assert_true(cov > npix() / 8);
        assert_int_equal(bad, 0);
        free(px);
    }
    for (size_t t = 0; t < technique_count(); t++) {
        const technique_desc *d = technique_at(t);
        if (d->test_only || d->cpu_displace)
            continue;
        char spec[128];
        snprintf(spec, sizeof spec, "technique=%s mesh=plane maps=bricks", d->name);
        float *px = render(spec);
        size_t bad = 0, cov = 0;
        for (size_t i = 0; i < npix(); i++) {
            const float *p = px + 4 * i;
            double n[3] = {2 * p[0] - 1, 2 * p[1] - 1, 2 * p[2] - 1};
            cov += p[3] > 0;
            bad += p[3] > 0 && (fabs(sqrt(dot(n, n)) - 1) > 0.01 || n[1] <= 0);
        }
        if (bad || cov < npix() / 8)
            fail_msg("normals view, %s: %zu of %zu covered px not a unit upward normal", spec,
                     bad, cov);
        free(px);
    }
    assert_int_equal(render_set_debug_view(F.r, RENDER_DEBUG_NONE), 0);
}

/* Renders frame `frame` of spec (its orbits turned by frame × degrees). */
static float *render_frame(const char *spec, uint64_t frame)
{
    render_item it = spec_prepare(F.r, spec, 0, NULL);
    assert_int_equal(render_set_frame(F.r, it, frame), 0);
    assert_int_equal(render_draw(F.r, it, F.w, F.h), 0);
    float *px = malloc((size_t)F.w * (size_t)F.h * 4 * sizeof(float));
    glReadPixels(0, 0, F.w, F.h, GL_RGBA, GL_FLOAT, px);
    render_release(F.r, it);
    return px;
}

/* Moving camera and lights (S2's light circles): frame k of an orbit is
 * bit-identical to a still render at the azimuths turned by k × degrees
 * (camera 30 + 3·10 = 60, lights 45 + 3·15 = 90 on top of it); frame 0 is
 * the still scene; and the path really moves. */
static void test_orbit_per_frame(void **state)
{
    (void)state;
    const char *base = "technique=pom mesh=cube light_count=8";
    char moving[256], still[256];
    snprintf(moving, sizeof moving, "%s camera.orbit_deg_per_frame=10 light.orbit_deg_per_frame=15", base);
    snprintf(still, sizeof still, "%s camera.azimuth=60 light.azimuth=90", base);
    size_t bytes = npix() * 4 * sizeof(float);
    float *k3 = render_frame(moving, 3), *at = render(still);
    assert_memory_equal(k3, at, bytes);
    float *k0 = render_frame(moving, 0), *plain = render(base);
    assert_memory_equal(k0, plain, bytes);
    assert_true(psnr(k0, k3, npix()) < 30.0);
    /* the lights alone: frame 2 at 20°/frame = light.azimuth 85 */
    free(k3);
    free(at);
    snprintf(moving, sizeof moving, "%s light.orbit_deg_per_frame=20", base);
    snprintf(still, sizeof still, "%s light.azimuth=85", base);
    k3 = render_frame(moving, 2);
    at = render(still);
    assert_memory_equal(k3, at, bytes);
    assert_true(psnr(k3, plain, npix()) < 60.0);
    free(k3);
    free(at);
    free(k0);
    free(plain);
}

/* specular_map: on scales each light's specular term by the material's
 * specular map, `flat` holds 0.5 everywhere: the image is the Lambert image
 * plus half the Blinn-Phong highlight, pixel by pixel (so a zero map leaves
 * no highlight), and the highlight is really there. */
static void test_specular_map(void **state)
{
    (void)state;
#define SPEC_BASE "technique=normal mesh=sphere maps=flat light_count=3"
    float *a = render(SPEC_BASE), *b = render(SPEC_BASE " lighting=lambert"),
          *c = render(SPEC_BASE " specular_map=on");
#undef SPEC_BASE
    double num = 0, den = 0, top = 0;
    for (size_t i = 0; i < 4 * npix(); i++) {
        double h = (double)a[i] - b[i];
        num += ((double)c[i] - b[i]) * h;
        den += h * h;
        top = fmax(top, h);
    }
    double k = num / den, worst = 0;
    for (size_t i = 0; i < 4 * npix(); i++)
        worst = fmax(worst, fabs((double)c[i] - b[i] - k * ((double)a[i] - b[i])));
    print_message("specular_map on: highlight x %.4f, worst residual %.2e, highlight peak %.3f\n", k, worst, top);
    assert_true(top > 0.2);
    assert_true(fabs(k - 128.0 / 255.0) < 2e-3);   /* 0.5 stored in 8 bits */
    assert_true(worst < 1e-4);
    free(a);
    free(b);
    free(c);
}

DM_TEST_MAIN(setup, teardown,
             cmocka_unit_test(test_light_on_surface),
             cmocka_unit_test(test_mirror_lobe),
             cmocka_unit_test(test_light_axes),
             cmocka_unit_test(test_camera_target_pans),
             cmocka_unit_test(test_normals_view),
             cmocka_unit_test(test_orbit_per_frame),
             cmocka_unit_test(test_specular_map))
