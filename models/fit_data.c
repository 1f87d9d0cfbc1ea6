/* fit_data.c — CSV tables for fits (see fit_data.h). */
#include "models/fit_data.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"

/* Cursor over one line: cell [start, end) and the 1-based column. */
typedef struct fit_data__cell { const char *start; size_t len, col; } fit_data__cell;

/* Splits line (len bytes) into cells, trimmed; returns the count (cells may
 * be NULL to count only). */
static size_t fit_data__split(const char *line, size_t len, fit_data__cell *cells)
{
    size_t n = 0, i = 0;
    for (;;) {
        size_t s = i;
        while (i < len && line[i] != ',')
            i++;
        size_t a = s, b = i;
        while (a < b && isspace((unsigned char)line[a]))
            a++;
        while (b > a && isspace((unsigned char)line[b - 1]))
            b--;
        if (cells)
            cells[n] = (fit_data__cell){ line + a, b - a, a + 1 };
        n++;
        if (i >= len)
            return n;
        i++;
    }
}

/* 1 when a column name is one a formula can use as a variable: a letter or
 * '_', then letters, digits, '_' or '.' (axes such as camera.distance). */
static int fit_data__name_ok(const char *s, size_t len)
{
    if (!len || !(isalpha((unsigned char)s[0]) || s[0] == '_'))
        return 0;
    for (size_t i = 1; i < len; i++)
        if (!(isalnum((unsigned char)s[i]) || s[i] == '_' || s[i] == '.'))
            return 0;
    return 1;
}

static int fit_data__header(fit_data *d, const char *line, size_t len, const char *path,
                            dm_str *err)
{
    d->n_cols = fit_data__split(line, len, NULL);
    fit_data__cell *c = dm_xmalloc(d->n_cols * sizeof *c);
    fit_data__split(line, len, c);
    d->names = dm_xcalloc(d->n_cols, sizeof *d->names);
    int rc = 0;
    for (size_t i = 0; i < d->n_cols && !rc; i++) {
        d->names[i] = strndup(c[i].start, c[i].len);
        for (size_t j = 0; j < i && !rc; j++)
            rc = !strcmp(d->names[i], d->names[j]);
        if (rc || !c[i].len) {
            dm_str_printf(err, "%s:1:%zu: %s column name '%s'", path, c[i].col,
                          c[i].len ? "duplicate" : "empty", d->names[i]);
            rc = DM_ERR_PARSE;
        } else if (!fit_data__name_ok(c[i].start, c[i].len)) {
            dm_str_printf(err, "%s:1:%zu: column name '%.*s' is not a name (letters, digits, "
                          "'_' and '.', starting with a letter or '_'), so a formula could "
                          "not read it", path, c[i].col, (int)(c[i].len > 64 ? 64 : c[i].len),
                          c[i].start);
            rc = DM_ERR_PARSE;
        }
    }
    free(c);
    return rc;
}

/* Parses one data row into d->values (already sized); lineno for messages. */
static int fit_data__row(fit_data *d, const char *line, size_t len, size_t lineno,
                         const char *path, dm_str *err)
{
    size_t n = fit_data__split(line, len, NULL);
    fit_data__cell *c = dm_xmalloc(n * sizeof *c);
    fit_data__split(line, len, c);
    double *row = d->values + d->n_rows * d->n_cols;
    int rc = 0;
    if (n != d->n_cols) {
        dm_str_printf(err, "%s:%zu:%zu: %zu cells, the header has %zu columns", path, lineno,
                      n > d->n_cols ? c[d->n_cols].col : len + 1, n, d->n_cols);
        rc = DM_ERR_PARSE;
    }
    for (size_t i = 0; i < n && !rc; i++) {
        char *cell = strndup(c[i].start, c[i].len), *end = NULL;
        row[i] = c[i].len ? strtod(cell, &end) : NAN;
        if (c[i].len && *end) {
            dm_str_printf(err, "%s:%zu:%zu: '%s' in column '%s' is not a number", path, lineno,
                          c[i].col, cell, d->names[i]);
            rc = DM_ERR_PARSE;
        }
        free(cell);
    }
    free(c);
    d->n_rows += !rc;
    return rc;
}

int fit_data_load_csv(const char *path, fit_data *out, dm_str *err)
{
    char *text = NULL;
    size_t len = 0, lineno = 0;
    int rc = 0;
    memset(out, 0, sizeof *out);
    if (dm_file_exists(path) && !dm_regular_file(path)) {
        dm_str_printf(err, "%s: cannot read the file: not a regular file (a directory, FIFO or "
                      "device)", path);
        return DM_ERR_IO;
    }
    if (dm_read_file(path, &text, &len) != 0) {
        dm_str_printf(err, "%s: cannot read the file", path);
        return DM_ERR_IO;
    }
    size_t n_lines = 1, bom = len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
    for (size_t i = 0; i < len; i++)
        n_lines += text[i] == '\n';
    if (memchr(text, '\0', len)) {
        dm_str_printf(err, "%s: a NUL byte: a CSV file is text", path);
        free(text);
        return DM_ERR_PARSE;
    }
    for (char *line = text + bom, *next; line && !rc; line = next) {   /* a UTF-8 BOM is skipped */
        next = strchr(line, '\n');
        size_t l = next ? (size_t)(next - line) : strlen(line);
        next = next ? next + 1 : NULL;
        lineno++;
        if (l && line[l - 1] == '\r')
            l--;
        if (l == 0 || strspn(line, " \t") == l)
            continue;
        if (!out->names) {
            rc = fit_data__header(out, line, l, path, err);
            out->values = dm_xmalloc((n_lines * out->n_cols + 1) * sizeof *out->values);
        } else {
            rc = fit_data__row(out, line, l, lineno, path, err);
        }
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
