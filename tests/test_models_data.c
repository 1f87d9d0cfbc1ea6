/* test_models_data.c — CSV tables for fits, with temporary files. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include "test_util.h"

#include "core/dm_error.h"
#include "models/fit_data.h"

/* Writes text to a new temporary file; returns its malloc'd path. */
static char *temp_csv(const char *text)
{
    char *path = strdup("/tmp/test_models_data_XXXXXX");
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, text, strlen(text)), (ssize_t)strlen(text));
    close(fd);
    return path;
}

/* Loads text as a CSV file into d (which the caller frees); fails the test
 * when it does not load. */
static void load_text(const char *text, fit_data *d)
{
    char *path = temp_csv(text);
    dm_str err = { 0 };
    assert_int_equal(fit_data_load_csv(path, d, &err), 0);
    dm_str_free(&err);
    unlink(path);
    free(path);
}

/* Fits formula to the column response of d; fails the test when the fit
 * cannot be made. */
static dm_fit_result fit_columns(fit_data *d, const char *formula, const char *response)
{
    fit_desc desc;
    dm_fit_result r;
    dm_str err = { 0 };
    assert_int_equal(fit_data_desc(d, formula, response, &desc, &err), 0);
    assert_int_equal(fit_run(&desc, &r, &err), 0);
    dm_str_free(&err);
    return r;
}

/* d refuses column response as the response of a fit, with message. */
static void expect_bad_response(fit_data *d, const char *response, const char *message)
{
    fit_desc desc;
    dm_str err = { 0 };
    assert_int_equal(fit_data_desc(d, "a", response, &desc, &err), DM_ERR_UNKNOWN);
    assert_string_equal(dm_str_get(&err), message);
    dm_str_free(&err);
}

static void load_and_fit(void **state)
{
    (void)state;
    /* t = 5 + 2 L exactly; one missing cell excludes its row */
    fit_data d;
    load_text("L, t ,other\r\n1,7,0\n2,9,0\n\n3, 11 ,1\n4,13,\n5,,2\n6,17,1e3\n", &d);
    assert_int_equal(d.n_cols, 3);
    assert_int_equal(d.n_rows, 6);
    assert_string_equal(d.names[1], "t");
    assert_true(d.values[2 * 3 + 1] == 11.0 && d.values[5 * 3 + 2] == 1000.0);
    assert_true(isnan(d.values[3 * 3 + 2]));
    dm_fit_result r = fit_columns(&d, "a + b*L", "t");
    assert_int_equal(r.n_points, 5);
    assert_int_equal(r.n_excluded, 1);
    assert_true(fabs(r.params[0].value - 5.0) < 1e-9 && fabs(r.params[1].value - 2.0) < 1e-9);
    dm_fit_result_free(&r);
    expect_bad_response(&d, "T", "fit: response 'T' is not a column (columns: L t other)");
    fit_data_free(&d);
}

/* dmbench's own results.csv shape: RFC 4180 quoting (a comma, a doubled
 * quote and a line break inside quotes), text columns beside numbers. */
static void rfc4180_and_text_columns(void **state)
{
    (void)state;
    fit_data d;
    load_text("key,scene,reason,L,t_ms\r\n"
              "57b7ede18e7a9e86,plane@80x45,,1,7\r\n"
              "a1,\"cube, big\",\"said \"\"no\"\"\r\nthen, crashed\",2,9\r\n"
              "b2,plane@80x45,,3,11\r\n", &d);
    assert_int_equal(d.n_cols, 5);
    assert_int_equal(d.n_rows, 3);
    assert_int_equal(d.text[0], 1);
    assert_int_equal(d.text[1], 1);
    assert_int_equal(d.text[2], 1);
    assert_int_equal(d.text[3], 2);
    assert_true(d.values[2 * 5 + 3] == 3.0 && d.values[1 * 5 + 4] == 9.0);
    assert_true(isnan(d.values[1 * 5 + 1]));
    dm_fit_result r = fit_columns(&d, "a + b*L", "t_ms");
    assert_true(fabs(r.params[0].value - 5.0) < 1e-9 && fabs(r.params[1].value - 2.0) < 1e-9);
    dm_fit_result_free(&r);
    expect_bad_response(&d, "scene", "fit: response 'scene' is a text column, not numbers");
    fit_data_free(&d);
}

/* 1 when one of r's warnings starts with prefix. */
static int has_warning(const dm_fit_result *r, const char *prefix)
{
    for (size_t i = 0; i < r->n_warnings; i++)
        if (strncmp(r->warnings[i], prefix, strlen(prefix)) == 0)
            return 1;
    return 0;
}

/* y unrelated to x: R² far below 0.8 and CV-MAPE above 20 % are warned
 * about; the exact line of load_and_fit is not. */
static void poor_fit_warns(void **state)
{
    (void)state;
    fit_data d;
    load_text("x,y\n1,10\n2,30\n3,12\n4,28\n5,11\n6,31\n7,10\n8,29\n9,12\n10,30\n", &d);
    dm_fit_result r = fit_columns(&d, "a + b*x", "y");
    assert_true(r.r2 < 0.1);
    assert_true(has_warning(&r, "poor fit: R² "));
    assert_true(r.cv_mape > FIT_POOR_CV_MAPE);
    assert_true(has_warning(&r, "poor prediction: CV-MAPE "));
    dm_fit_result_free(&r);
    r = fit_columns(&d, "a + b*x", "x");   /* x = a + b x: exact */
    assert_false(has_warning(&r, "poor "));
    dm_fit_result_free(&r);
    fit_data_free(&d);
}

static void expect_parse_error(const char *text, const char *tail)
{
    char *path = temp_csv(text);
    fit_data d;
    dm_str err = { 0 }, want = { 0 };
    assert_int_equal(fit_data_load_csv(path, &d, &err), DM_ERR_PARSE);
    assert_null(d.names);
    dm_str_printf(&want, "%s:%s", path, tail);
    assert_string_equal(dm_str_get(&err), dm_str_get(&want));
    dm_str_free(&err);
    dm_str_free(&want);
    unlink(path);
    free(path);
}

static void bad_cells(void **state)
{
    (void)state;
    expect_parse_error("L,t\n1,2\n3, 4x\n", "3:4: '4x' in column 't' is not a number");
    expect_parse_error("L,t\n1,2,3\n", "2:5: 3 cells, the header has 2 columns");
    expect_parse_error("L,t\n1\n", "2:2: 1 cells, the header has 2 columns");
    expect_parse_error("L,,t\n", "1:3: empty column name ''");
    expect_parse_error("L,t,L\n", "1:5: duplicate column name 'L'");
    expect_parse_error("\n\n", "1:1: no header row");
    expect_parse_error("L,t\n1,\"2\n", "2:3: unterminated quoted field");
    fit_data d;
    dm_str err = { 0 };
    assert_int_equal(fit_data_load_csv("/nonexistent/x.csv", &d, &err), DM_ERR_IO);
    dm_str_free(&err);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(load_and_fit),
             cmocka_unit_test(bad_cells),
             cmocka_unit_test(rfc4180_and_text_columns),
             cmocka_unit_test(poor_fit_warns))
