/* test_viewer_state.c — the viewer's input handling, key scripts and font,
 * without GL (the GL side is covered by test_viewer.sh under xvfb-run). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "test_util.h"

#include "core/dm_error.h"
#include "viewer/viewer_overlay.h"
#include "viewer/viewer_script.h"
#include "viewer/viewer_state.h"
#include "techniques/technique.h"

static void state_with(viewer_state *st, const char *k1, const char *v1, const char *k2, const char *v2)
{
    dm_kv *kv = NULL;
    size_t n = 0;
    if (k1)
        dm_kv_push(&kv, &n, k1, v1);
    if (k2)
        dm_kv_push(&kv, &n, k2, v2);
    viewer_state_init(st, kv, n);
    dm_kv_free(kv, n);
    st->dirty = 0;
}

static void type(viewer_state *st, const char *keys)
{
    for (const char *p = keys; *p; p++)
        viewer_state_char(st, (unsigned char)*p);
}

static void test_level_doubles_and_halves_steps(void **s)
{
    (void)s;
    viewer_state st;
    state_with(&st, "technique", "steep-parallax", NULL, NULL);
    type(&st, "]");                       /* default 32 → 64 */
    assert_string_equal(viewer_state_get(&st, "steps"), "64");
    assert_int_equal(st.dirty, 1);
    type(&st, "[[[");                     /* 64 → 32 → 16 → 8 */
    assert_string_equal(viewer_state_get(&st, "steps"), "8");
    type(&st, "[[[[");                    /* 8 → 4 → 2 → 1 → 1 (axis minimum) */
    assert_string_equal(viewer_state_get(&st, "steps"), "1");
    viewer_state_free(&st);
}

static void test_level_on_technique_without_levels_says_why(void **s)
{
    (void)s;
    viewer_state st;
    state_with(&st, "technique", "normal", NULL, NULL);
    type(&st, "]");
    assert_int_equal(st.dirty, 0);
    assert_non_null(strstr(dm_str_get(&st.msg), "reads neither tess_level nor steps"));
    assert_string_equal(viewer_state_get(&st, "tess_level"), "1");
    viewer_state_free(&st);
}

static void test_digits_pick_techniques_in_registry_order(void **s)
{
    (void)s;
    const char *const *names = technique_names();
    size_t count = 0;
    while (names[count])
        count++;
    viewer_state st;
    state_with(&st, "technique", "pom", NULL, NULL);
    type(&st, "2");
    assert_string_equal(viewer_state_get(&st, "technique"), names[1]);
    type(&st, "1");
    assert_string_equal(viewer_state_get(&st, "technique"), names[0]);
    type(&st, "0");                       /* the tenth, when there is one */
    assert_string_equal(viewer_state_get(&st, "technique"), count >= 10 ? names[9] : names[0]);
    viewer_state_free(&st);
}

static void test_filter_cycles_and_wraps(void **s)
{
    (void)s;
    viewer_state st;
    state_with(&st, NULL, NULL, NULL, NULL);
    type(&st, "f");                       /* trilinear (default) → aniso2 */
    assert_string_equal(viewer_state_get(&st, "filter"), "aniso2");
    type(&st, "FFF");                     /* aniso4, aniso8, aniso16 */
    assert_string_equal(viewer_state_get(&st, "filter"), "aniso16");
    type(&st, "f");
    assert_string_equal(viewer_state_get(&st, "filter"), "nearest");
    viewer_state_free(&st);
}

static void test_height_scale_steps_only_where_read(void **s)
{
    (void)s;
    viewer_state st;
    state_with(&st, "technique", "bump", NULL, NULL);
    type(&st, "h");
    assert_string_equal(viewer_state_get(&st, "height_scale"), "0.07");
    type(&st, "HH");
    assert_string_equal(viewer_state_get(&st, "height_scale"), "0.05");
    viewer_state_free(&st);
    state_with(&st, "technique", "texture", NULL, NULL);
    type(&st, "h");
    assert_string_equal(viewer_state_get(&st, "height_scale"), "0.06");
    assert_non_null(strstr(dm_str_get(&st.msg), "does not read height_scale"));
    assert_int_equal(st.dirty, 0);
    viewer_state_free(&st);
}

static void test_mouse_orbit_zoom_and_reset(void **s)
{
    (void)s;
    viewer_state st;
    state_with(&st, "camera.distance", "5", NULL, NULL);
    viewer_state_orbit(&st, 40, -20);     /* 0.25°/px: azimuth 30 − 10, elevation 20 − 5 */
    assert_string_equal(viewer_state_get(&st, "camera.azimuth"), "20");
    assert_string_equal(viewer_state_get(&st, "camera.elevation"), "15");
    viewer_state_orbit(&st, 0, 1000);     /* clamped below the pole */
    assert_string_equal(viewer_state_get(&st, "camera.elevation"), "89");
    viewer_state_orbit(&st, -800, 0);     /* 20 + 200 = 220 → wraps to −140 */
    assert_string_equal(viewer_state_get(&st, "camera.azimuth"), "-140");
    viewer_state_zoom(&st, 2);            /* 5 · 0.9² */
    assert_string_equal(viewer_state_get(&st, "camera.distance"), "4.05");
    type(&st, "r");
    assert_string_equal(viewer_state_get(&st, "camera.distance"), "5");
    assert_string_equal(viewer_state_get(&st, "camera.azimuth"), "30");
    assert_string_equal(viewer_state_get(&st, "camera.elevation"), "20");
    viewer_state_free(&st);
}

static void test_toggles_and_requests(void **s)
{
    (void)s;
    viewer_state st;
    state_with(&st, NULL, NULL, NULL, NULL);
    type(&st, "wcts?");
    assert_int_equal(st.wireframe, 1);
    assert_int_equal(st.overlay, 1);
    assert_int_equal(st.want_timed, 1);
    assert_int_equal(st.want_screenshot, 1);
    assert_int_equal(st.want_help, 1);
    assert_int_equal(st.dirty, 0);        /* none of them changes the configuration */
    assert_int_equal(st.want_quit, 0);
    viewer_state_special(&st, VIEWER_KEY_ESC);
    assert_int_equal(st.want_quit, 1);
    assert_int_equal(viewer_state_set(&st, "filter", "bogus"), DM_ERR_ARG);
    assert_int_equal(viewer_state_set(&st, "nosuchaxis", "1"), DM_ERR_UNKNOWN);
    viewer_state_free(&st);
}

/* L: light.azimuth advances exactly VIEWER_LIGHT_ORBIT_DEG per tick while on
 * (wrapping at 180); N toggles the normals view and asks for a re-prepare. */
static void test_light_orbit_and_normals(void **s)
{
    (void)s;
    viewer_state st;
    state_with(&st, "light.azimuth", "170", NULL, NULL);
    viewer_state_tick(&st);                   /* orbit off: nothing moves */
    assert_string_equal(viewer_state_get(&st, "light.azimuth"), "170");
    assert_int_equal(st.dirty, 0);
    type(&st, "L");
    assert_int_equal(st.light_orbit, 1);
    assert_non_null(strstr(dm_str_get(&st.msg), "light orbit on"));
    for (int k = 0; k < 4; k++)
        viewer_state_tick(&st);               /* 170 + 4·2 = 178 */
    assert_string_equal(viewer_state_get(&st, "light.azimuth"), "178");
    assert_int_equal(st.dirty, 1);
    viewer_state_tick(&st);                   /* 180 wraps to −180 */
    viewer_state_tick(&st);
    assert_string_equal(viewer_state_get(&st, "light.azimuth"), "-178");
    type(&st, "l");
    viewer_state_tick(&st);
    assert_string_equal(viewer_state_get(&st, "light.azimuth"), "-178");
    st.dirty = 0;
    type(&st, "N");
    assert_int_equal(st.normals, 1);
    assert_int_equal(st.dirty, 1);
    type(&st, "n");
    assert_int_equal(st.normals, 0);
    assert_non_null(strstr(viewer_state_help(), "N  normals view"));
    assert_non_null(strstr(viewer_state_help(), "right drag pans"));
    viewer_state_free(&st);
}

/* A plays the frame index along camera.path (one per tick), > and < step it
 * and pause; back from 0 goes to the path's last frame; on a still path
 * with no orbit per frame nothing moves, and A says why and stays off.  The
 * frame index never marks the state dirty (no re-prepare: render_set_frame). */
static void test_path_play_and_step(void **s)
{
    (void)s;
    viewer_state st;
    state_with(&st, NULL, NULL, NULL, NULL);
    type(&st, "A");
    assert_int_equal(st.playing, 0);
    assert_non_null(strstr(dm_str_get(&st.msg), "nothing moves with the frame"));
    viewer_state_tick(&st);
    assert_int_equal((int)st.frame, 0);
    viewer_state_free(&st);

    state_with(&st, "camera.path", "dolly", "camera.path_frames", "12");
    assert_int_equal((int)viewer_state_path_frames(&st), 12);
    type(&st, "<");                            /* back from 0: the last frame */
    assert_int_equal((int)st.frame, 11);
    assert_non_null(strstr(dm_str_get(&st.msg), "dolly paused, frame 11 (12 of 12 along the path)"));
    type(&st, ">>");
    assert_int_equal((int)st.frame, 13);       /* 13 mod 12: the path's second frame */
    type(&st, "a");
    assert_int_equal(st.playing, 1);
    for (int k = 0; k < 5; k++)
        viewer_state_tick(&st);
    assert_int_equal((int)st.frame, 18);
    type(&st, ">");                            /* a step pauses */
    assert_int_equal(st.playing, 0);
    assert_int_equal((int)st.frame, 19);
    viewer_state_tick(&st);
    assert_int_equal((int)st.frame, 19);
    assert_int_equal(st.dirty, 0);
    assert_non_null(strstr(viewer_state_help(), "play / pause camera.path"));
    viewer_state_free(&st);

    state_with(&st, "camera.orbit_deg_per_frame", "3", NULL, NULL);   /* still, but it turns */
    assert_int_equal((int)viewer_state_path_frames(&st), 0);
    type(&st, "A");
    assert_int_equal(st.playing, 1);
    viewer_state_tick(&st);
    assert_int_equal((int)st.frame, 1);
    viewer_state_free(&st);
}

/* Right-drag pan: target += distance·0.002·(−dx·right + dy·up).  At azimuth
 * 90, elevation 0, distance 5: right = (0, 0, −1), up = (0, 1, 0), so a pan
 * of (100, −50) px moves the target by 0.01·(0, −50, 100) = (0, −0.5, 1);
 * R brings it back to the command line's target. */
static void test_pan_and_reset(void **s)
{
    (void)s;
    viewer_state st;
    state_with(&st, "camera.azimuth", "90", "camera.elevation", "0");
    viewer_state_set(&st, "camera.distance", "5");
    viewer_state_pan(&st, 100, -50);
    assert_string_equal(viewer_state_get(&st, "camera.target_x"), "0");
    assert_string_equal(viewer_state_get(&st, "camera.target_y"), "-0.5");
    assert_string_equal(viewer_state_get(&st, "camera.target_z"), "1");
    viewer_state_set(&st, "camera.azimuth", "0");   /* right = +X: dx 10 → x −0.1 */
    viewer_state_pan(&st, 10, 0);
    assert_string_equal(viewer_state_get(&st, "camera.target_x"), "-0.1");
    assert_string_equal(viewer_state_get(&st, "camera.target_z"), "1");
    type(&st, "R");
    assert_string_equal(viewer_state_get(&st, "camera.target_x"), "0");
    assert_string_equal(viewer_state_get(&st, "camera.target_y"), "0");
    assert_string_equal(viewer_state_get(&st, "camera.target_z"), "0");
    assert_string_equal(viewer_state_get(&st, "camera.azimuth"), "90");
    viewer_state_free(&st);
}

static void test_restore_undoes_without_dirty(void **s)
{
    (void)s;
    viewer_state st;
    state_with(&st, "technique", "bump", NULL, NULL);
    dm_kv good = {"technique", "phong"};
    type(&st, "m");
    viewer_state_restore(&st, &good, 1);
    assert_int_equal(st.dirty, 0);
    assert_int_equal(st.n_params, 1);
    assert_string_equal(viewer_state_get(&st, "technique"), "phong");
    assert_string_equal(viewer_state_get(&st, "mesh"), "plane");   /* back to the default */
    viewer_state_free(&st);
}

static void test_script_events(void **s)
{
    (void)s;
    viewer_event *ev = NULL;
    size_t n = 0;
    dm_str err = {0};
    assert_int_equal(viewer_script_parse("a H. {wait:2}{ESC}{drag:3,-4}{wheel:-1}{space}{dot}"
                                         "{pan:-5,7}", &ev, &n, &err), 0);
    assert_int_equal(n, 11);
    assert_int_equal(ev[10].kind, VIEWER_EV_PAN);
    assert_true(ev[10].dx == -5.0 && ev[10].dy == 7.0);
    assert_int_equal(ev[0].kind, VIEWER_EV_CHAR);
    assert_int_equal(ev[0].ch, 'a');
    assert_int_equal(ev[1].ch, 'H');
    for (int i = 2; i < 5; i++)
        assert_int_equal(ev[i].kind, VIEWER_EV_WAIT);
    assert_int_equal(ev[5].kind, VIEWER_EV_ESC);
    assert_int_equal(ev[6].kind, VIEWER_EV_DRAG);
    assert_true(ev[6].dx == 3.0 && ev[6].dy == -4.0);
    assert_int_equal(ev[7].kind, VIEWER_EV_WHEEL);
    assert_true(ev[7].dy == -1.0);
    assert_int_equal(ev[8].ch, ' ');
    assert_int_equal(ev[9].ch, '.');
    free(ev);
}

static void test_script_errors_name_the_offset(void **s)
{
    (void)s;
    static const char *const bad[] = {"ab{bogus}", "ab{wait:3", "ab{wait:-1}", "ab{drag:1}"};
    for (size_t i = 0; i < 4; i++) {
        viewer_event *ev = NULL;
        size_t n = 99;
        dm_str err = {0};
        assert_int_equal(viewer_script_parse(bad[i], &ev, &n, &err), DM_ERR_PARSE);
        assert_null(ev);
        assert_int_equal(n, 99);
        assert_non_null(strstr(dm_str_get(&err), "offset 2"));
        dm_str_free(&err);
    }
}

static size_t lit(const uint8_t *px, int w, int h)
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
        n += px[4 * i] == 255;
    return n;
}

static void test_font_raster_sizes_and_pixels(void **s)
{
    (void)s;
    int w = 0, h = 0;
    uint8_t *px = viewer_font_raster("1", 1, &w, &h);
    assert_int_equal(w, 4 + 1);            /* cell 3+1, margin 1 */
    assert_int_equal(h, 6 + 1);
    assert_int_equal(lit(px, w, h), 8);    /* the '1' glyph has 8 lit pixels */
    assert_int_equal(px[3], 255);          /* opaque box */
    free(px);
    px = viewer_font_raster("A\nb", 2, &w, &h);   /* 'b' drawn as 'B'; 10 + 10 pixels, 2×2 each */
    assert_int_equal(w, 8 + 2);
    assert_int_equal(h, 24 + 2);
    assert_int_equal(lit(px, w, h), 80);
    free(px);
    uint8_t *q = viewer_font_raster("~", 1, &w, &h), *r = viewer_font_raster("?", 1, &w, &h);
    assert_memory_equal(q, r, (size_t)w * (size_t)h * 4);   /* unknown shown as '?' */
    free(q);
    free(r);
    assert_null(viewer_font_raster("", 1, &w, &h));
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_level_doubles_and_halves_steps),
             cmocka_unit_test(test_level_on_technique_without_levels_says_why),
             cmocka_unit_test(test_digits_pick_techniques_in_registry_order),
             cmocka_unit_test(test_filter_cycles_and_wraps),
             cmocka_unit_test(test_height_scale_steps_only_where_read),
             cmocka_unit_test(test_mouse_orbit_zoom_and_reset),
             cmocka_unit_test(test_toggles_and_requests),
             cmocka_unit_test(test_light_orbit_and_normals),
             cmocka_unit_test(test_path_play_and_step),
             cmocka_unit_test(test_pan_and_reset),
             cmocka_unit_test(test_restore_undoes_without_dirty),
             cmocka_unit_test(test_script_events),
             cmocka_unit_test(test_script_errors_name_the_offset),
             cmocka_unit_test(test_font_raster_sizes_and_pixels))
