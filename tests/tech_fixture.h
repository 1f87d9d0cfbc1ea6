/* tech_fixture.h — the GL fixture shared by the techniques GL tests. */
#ifndef TESTS_TECH_FIXTURE_H
#define TESTS_TECH_FIXTURE_H

#include <epoxy/gl.h>
#include "tests/tech_spec.h"
#include "run/gl_context.h"
#include "techniques/render.h"

typedef struct fixture {
    gl_context *ctx;
    render_ctx *r;
    GLuint fbo, color, depth;
    int w, h;
} fixture;

extern fixture F;

/* (Re)creates and binds an RGBA32F + depth24 target of w x h. */
void target(int w, int h);
/* cmocka group setup: context, renderer, a w x h target; -1 without GL. */
int techfix_setup(void **state, int w, int h);
int teardown(void **state);

/* Prepares and draws spec into the target; returns w*h RGBA floats (caller frees). */
float *render(const char *spec);
size_t non_finite(const float *px, size_t n);
double luma_stddev(const float *px, size_t n);
/* PSNR over RGB with peak 1 (INFINITY when identical). */
double psnr(const float *a, const float *b, size_t n);
size_t npix(void);
/* Values of w*h RGBA that are non-finite or outside [0, 1e4]. */
size_t out_of_range(const float *px, size_t n);
/* Renders spec and fails the test when a value is out of range. */
void render_expect_in_range(const char *spec);
/* Draws spec once (warm-up: llvmpipe compiles at the first draw), then once
 * inside one query of each of the n (at most 8) targets; out[i] gets the
 * result of targets[i], e.g. GL_TESS_EVALUATION_SHADER_INVOCATIONS_ARB. */
void draw_queried(const char *spec, const GLenum *targets, int n, GLuint64 *out);

#endif
