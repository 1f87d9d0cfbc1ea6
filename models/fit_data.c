/* fit_data.c — CSV tables for fits (see fit_data.h). */
#include "models/fit_data.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <errno.h>
#include <string.h>

#include "core/dm_error.h"

/* One cell of a record: its text (unquoted, "" unescaped, trimmed when it
 * was not quoted) and where it starts (1-based line and column). */
typedef struct fit_data__cell { char *text; size_t line, col; } fit_data__cell;

/* Reads one RFC 4180 record starting at *pos (a quoted field may hold ',',
 * '""' and line breaks; CRLF or LF ends a record).  Fills *cells (malloc'd,
 * *n of them, also on failure) and advances *pos and *line past the record.
 * Returns 0 or DM_ERR_PARSE for an unterminated quote (err names where it
 * opened). */
static int fit_data__record(const char *t, size_t len, size_t *pos, size_t *line,
                            fit_data__cell **cells, size_t *n, const char *path, dm_str *err)
{
    size_t i = *pos, bol = *pos, cap = 8;
    *cells = dm_xmalloc(cap * sizeof **cells);
    *n = 0;
    for (;;) {
        dm_str v = {0};
        while (i < len && (t[i] == ' ' || t[i] == '\t'))
            i++;
        fit_data__cell c = { NULL, *line, i - bol + 1 };
        if (i < len && t[i] == '"') {
            for (i++; i < len && !(t[i] == '"' && (i + 1 >= len || t[i + 1] != '"')); i++) {
                *line += t[i] == '\n';
                dm_str_catn(&v, &t[i], 1);
                i += t[i] == '"';
            }
            if (i >= len) {
                dm_str_printf(err, "%s:%zu:%zu: unterminated quoted field", path, c.line, c.col);
                dm_str_free(&v);
                return DM_ERR_PARSE;
            }
            for (i++; i < len && t[i] != ',' && t[i] != '\n'; i++)
                ;
        } else {
            size_t a = i;
            while (i < len && t[i] != ',' && t[i] != '\n')
                i++;
            size_t b = i;
            while (b > a && isspace((unsigned char)t[b - 1]))
                b--;
            dm_str_catn(&v, t + a, b - a);
        }
        c.text = dm_xstrdup(dm_str_get(&v));
        dm_str_free(&v);
        if (*n == cap)
            *cells = dm_xrealloc(*cells, (cap *= 2) * sizeof **cells);
        (*cells)[(*n)++] = c;
        if (i >= len || t[i] == '\n') {
            *line += i < len;
            *pos = i + (i < len);
            return 0;
        }
        i++;
    }
}

static void fit_data__cells_free(fit_data__cell *c, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(c[i].text);
    free(c);
}

/* A column name and its position, sorted by name then position. */
typedef struct fit_data__named { const char *name; size_t i; } fit_data__named;
static int fit_data__by_name(const void *a, const void *b)
{
    const fit_data__named *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    return c ? c : (x->i > y->i) - (x->i < y->i);
}

/* The first column (in file order) whose name an earlier column has, or n.
 * Sorted, not pairwise: a header of 10^5 columns is checked in
 * milliseconds, not minutes. */
static size_t fit_data__first_duplicate(const fit_data *d, size_t n)
{
    fit_data__named *v = dm_xcalloc(n ? n : 1, sizeof *v);
    size_t first = n;
    for (size_t i = 0; i < n; i++)
        v[i] = (fit_data__named){ d->names[i], i };
    qsort(v, n, sizeof *v, fit_data__by_name);
    for (size_t k = 1; k < n; k++)
        if (!strcmp(v[k].name, v[k - 1].name) && v[k].i < first)
            first = v[k].i;
    free(v);
    return first;
}

static int fit_data__header(fit_data *d, fit_data__cell *c, size_t n, const char *path,
                            dm_str *err)
{
    d->n_cols = n;
    d->names = dm_xcalloc(n, sizeof *d->names);
    d->text = dm_xcalloc(n, sizeof *d->text);
    size_t bad = n;
    for (size_t i = 0; i < n; i++) {
        d->names[i] = dm_xstrdup(c[i].text);
        if (!*c[i].text && bad == n)
            bad = i;
    }
    size_t dup = fit_data__first_duplicate(d, n);
    bad = dup < bad ? dup : bad;
    if (bad == n)
        return 0;
    dm_str_printf(err, "%s:%zu:%zu: %s column name '%s'", path, c[bad].line, c[bad].col,
                  *c[bad].text ? "duplicate" : "empty", d->names[bad]);
    return DM_ERR_PARSE;
}

/* 1 when text is a whole number as strtod reads it, stored in *v. */
static int fit_data__number(const char *text, double *v)
{
    char *end = NULL;
    *v = strtod(text, &end);
    return *text && !*end;
}

/* Parses one data record into d->values; a column whose first non-empty
 * cell is not a number is a text column (NaN everywhere, not a variable). */
static int fit_data__row(fit_data *d, fit_data__cell *c, size_t n, size_t lineno,
                         size_t len, const char *path, dm_str *err)
{
    if (n != d->n_cols) {
        dm_str_printf(err, "%s:%zu:%zu: %zu cells, the header has %zu columns", path, lineno,
                      n > d->n_cols ? c[d->n_cols].col : len + 1, n, d->n_cols);
        return DM_ERR_PARSE;
    }
    if (d->n_rows == d->cap)
        d->values = dm_xrealloc(d->values, (d->cap = d->cap * 2 + 16) * d->n_cols * sizeof *d->values);
    double *row = d->values + d->n_rows * d->n_cols;
    for (size_t i = 0; i < n; i++) {
        row[i] = NAN;
        if (!*c[i].text || d->text[i] == 1)
            continue;
        int num = fit_data__number(c[i].text, &row[i]);
        if (!num && d->text[i] == 2) {
            dm_str_printf(err, "%s:%zu:%zu: '%s' in column '%s' is not a number", path, c[i].line,
                          c[i].col, c[i].text, d->names[i]);
            return DM_ERR_PARSE;
        }
        d->text[i] = num ? 2 : 1;
        row[i] = num ? row[i] : NAN;
    }
    d->n_rows++;
    return 0;
}

/* 1 when the record is blank (one empty unquoted cell). */
static int fit_data__blank(const char *t, size_t from, size_t to)
{
    for (size_t i = from; i < to; i++)
        if (!isspace((unsigned char)t[i]))
            return 0;
    return 1;
}

int fit_data_load_csv(const char *path, fit_data *out, dm_str *err)
{
    char *text = NULL;
    size_t len = 0, pos = 0, line = 1;
    int rc = 0;
    memset(out, 0, sizeof *out);
    char why[256];
    if (dm_input_file(path, why, sizeof why) != 0) {
        dm_str_printf(err, "%s: cannot read the file: %s", path, why);
        return DM_ERR_IO;
    }
    if (dm_read_file(path, &text, &len) != 0) {
        dm_str_printf(err, "%s: cannot read the file: %s", path, strerror(errno));
        return DM_ERR_IO;
    }
    if (memchr(text, '\0', len)) {
        dm_str_printf(err, "%s: a NUL byte: a CSV file is text", path);
        free(text);
        return DM_ERR_PARSE;
    }
    if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0)
        pos = 3;                 /* a UTF-8 BOM is not part of the first column's name */
    while (pos < len && !rc) {
        size_t from = pos, lineno = line, n;
        fit_data__cell *c;
        rc = fit_data__record(text, len, &pos, &line, &c, &n, path, err);
        size_t l = pos - from - (pos > from && text[pos - 1] == '\n');
        l -= l && text[from + l - 1] == '\r';
        if (!rc && !fit_data__blank(text, from, from + l))
            rc = !out->names ? fit_data__header(out, c, n, path, err)
                             : fit_data__row(out, c, n, lineno, l, path, err);
        fit_data__cells_free(c, n);
    }
    if (!rc && !out->names) {
        dm_str_printf(err, "%s:1:1: no header row", path);
        rc = DM_ERR_PARSE;
    }
    free(text);
    if (rc)
        fit_data_free(out);
    return rc;
}

void fit_data_free(fit_data *d)
{
    for (size_t i = 0; d->names && i < d->n_cols; i++)
        free(d->names[i]);
    free(d->names);
    free(d->text);
    free(d->values);
    free(d->y);
    memset(d, 0, sizeof *d);
}

int fit_data_desc(fit_data *d, const char *formula, const char *response, fit_desc *desc,
                  dm_str *err)
{
    memset(desc, 0, sizeof *desc);
    size_t col = 0;
    while (col < d->n_cols && strcmp(d->names[col], response))
        col++;
    if (col < d->n_cols && d->text[col] == 1) {
        dm_str_printf(err, "fit: response '%s' is a text column, not numbers", response);
        return DM_ERR_UNKNOWN;
    }
    if (col == d->n_cols) {
        dm_str_printf(err, "fit: response '%s' is not a column (columns:", response);
        for (size_t i = 0; i < d->n_cols; i++)
            dm_str_printf(err, " %s", d->names[i]);
        dm_str_cat(err, ")");
        return DM_ERR_UNKNOWN;
    }
    free(d->y);
    d->y = dm_xmalloc((d->n_rows + 1) * sizeof *d->y);
    for (size_t i = 0; i < d->n_rows; i++)
        d->y[i] = d->values[i * d->n_cols + col];
    desc->formula = formula;
    desc->response = response;
    desc->variables = (const char *const *)d->names;
    desc->n_vars = d->n_cols;
    desc->x = d->values;
    desc->y = d->y;
    desc->n_points = d->n_rows;
    return 0;
}
