/* A 16384² map set through the renderer: generated, cached on disk, uploaded
 * with full mip chains in every map, drawn — without running out of memory
 * (the compact set is 2 GiB; the peak resident size is printed).  Slow
 * (tens of seconds), labelled `slow`. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <epoxy/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "run/gl_context.h"
#include "techniques/render.h"

static void test_16k(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm-bigmaps-XXXXXX";
    assert_non_null(mkdtemp(dir));
    setenv("DMBENCH_CACHE_DIR", dir, 1);
    gl_context *ctx;
    render_ctx *r;
    dm_str e = {0};
    assert_int_equal(gl_context_create(NULL, &ctx, &e), 0);
    assert_int_equal(render_create(&r), 0);
    dm_kv kv[] = {{"technique", "normal"}, {"maps", "checker"}, {"texture_size", "16384"},
                  {"resolution", "64x64"}};
    render_item it;
    int64_t t0 = dm_now_ns();
    assert_int_equal(render_prepare(r, kv, 4, &it, &e), 0);
    printf("prepare %.1f s: %s", (double)(dm_now_ns() - t0) / 1e9, dm_str_get(&e));
    assert_non_null(strstr(dm_str_get(&e), "maps 'checker' 16384²: generated in"));
    render_item_info info;
    assert_int_equal(render_get_info(r, it, &info), 0);
    /* normal rgb8 + albedo rgba8 chains: (3 + 4) bytes · 16384² · (1 + 1/4 + ...) */
    size_t want = 0;
    for (size_t s = 16384; s >= 1; s /= 2)
        want += 7 * s * s;
    assert_int_equal(info.texture_bytes, want);
    GLuint fbo, rb;
    glCreateFramebuffers(1, &fbo);
    glCreateRenderbuffers(1, &rb);
    glNamedRenderbufferStorage(rb, GL_RGBA8, 64, 64);
    glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    assert_int_equal(render_draw(r, it, 64, 64), 0);
    glFinish();
    assert_int_equal(glGetError(), GL_NO_ERROR);
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    printf("peak resident %.2f GiB\n", (double)ru.ru_maxrss / (1024.0 * 1024.0));
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &rb);
    render_destroy(r);
    gl_context_destroy(ctx);
    char *path = dm_xasprintf("%s/maps/checker-16384.dmmaps", dir), *sub = dm_xasprintf("%s/maps", dir);
    assert_true(dm_file_exists(path));
    remove(path);
    remove(sub);
    remove(dir);
    free(path);
    free(sub);
    dm_str_free(&e);
}

DM_TEST_MAIN(NULL, NULL, cmocka_unit_test(test_16k))
