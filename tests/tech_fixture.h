/* tech_fixture.h — the GL fixture shared by the techniques GL tests. */
#ifndef TESTS_TECH_FIXTURE_H
#define TESTS_TECH_FIXTURE_H

#include <epoxy/gl.h>
#include "harness/gl_context.h"
#include "techniques/render.h"

typedef struct fixture {
    gl_context *ctx;
    tech_renderer *r;
    GLuint fbo, color, depth;
    int w, h;
} fixture;

extern fixture F;

/* (Re)creates and binds an RGBA32F + depth24 target of w x h. */
void target(int w, int h);
/* cmocka group setup: context, renderer, a w x h target; -1 without GL. */
int techfix_setup(void **state, int w, int h);
int teardown(void **state);

#endif
