/* dm_table.c — plain-text tables that fit a width (see dm_table.h). */
#include "dm_table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void dm_table_row(dm_table *t)
{
    t->rows = dm_xrealloc(t->rows, (t->n_rows + 1) * sizeof *t->rows);
    t->n_cells = dm_xrealloc(t->n_cells, (t->n_rows + 1) * sizeof *t->n_cells);
    t->notes = dm_xrealloc(t->notes, (t->n_rows + 1) * sizeof *t->notes);
    t->rows[t->n_rows] = NULL;
    t->notes[t->n_rows] = NULL;
    t->n_cells[t->n_rows++] = 0;
}

void dm_table_cell(dm_table *t, const char *text)
{
    if (!t->n_rows)
        dm_table_row(t);
    size_t r = t->n_rows - 1;
    t->rows[r] = dm_xrealloc(t->rows[r], (t->n_cells[r] + 1) * sizeof *t->rows[r]);
    t->rows[r][t->n_cells[r]++] = dm_xstrdup(text ? text : "");
}

void dm_table_note(dm_table *t, const char *text)
{
    if (!t->n_rows)
        dm_table_row(t);
    free(t->notes[t->n_rows - 1]);
    t->notes[t->n_rows - 1] = text && *text ? dm_xstrdup(text) : NULL;
}

void dm_table_free(dm_table *t)
{
    for (size_t r = 0; r < t->n_rows; r++) {
        free(t->notes[r]);
        for (size_t c = 0; c < t->n_cells[r]; c++)
            free(t->rows[r][c]);
        free(t->rows[r]);
    }
    free(t->rows);
    free(t->n_cells);
    free(t->notes);
    memset(t, 0, sizeof *t);
}

size_t dm_text_width(const char *text)
{
    size_t n = 0;
    for (const unsigned char *p = (const unsigned char *)(text ? text : ""); *p; p++)
        n += (*p & 0xc0) != 0x80;   /* count lead bytes, not continuation bytes */
    return n;
}

static const char *table__cell(const dm_table *t, size_t r, size_t c)
{
    return c < t->n_cells[r] ? t->rows[r][c] : "";
}

static void table__pad(dm_str *out, size_t n)
{
    for (size_t i = 0; i < n; i++)
        dm_str_cat(out, " ");
}

void dm_wrap(const char *text, const char *first, const char *indent, size_t width, dm_str *out)
{
    dm_str line = {0};
    dm_str_cat(&line, first);
    size_t lead = dm_text_width(first), col = lead;
    const char *p = text ? text : "";
    while (*p) {
        while (*p == ' ')
            p++;
        size_t n = strcspn(p, " ");
        if (!n)
            break;
        const char *q = p + n;   /* a lone "%" stays with the number before it */
        while (*q == ' ')
            q++;
        if (*q == '%')
            n = (size_t)(q - p) + strcspn(q, " ");
        char *word = dm_xstrdup(p);
        word[n] = '\0';
        size_t ww = dm_text_width(word);
        if (col > lead && col + 1 + ww > width) {   /* the word goes on a new line */
            dm_str_cat(out, dm_str_get(&line));
            dm_str_cat(out, "\n");
            line.len = 0;
            line.buf[0] = '\0';
            dm_str_cat(&line, indent);
            col = lead = dm_text_width(indent);
        }
        if (col > lead) {
            dm_str_cat(&line, " ");
            col++;
        }
        dm_str_cat(&line, word);
        col += ww;
        free(word);
        p += n;
    }
    dm_str_cat(out, dm_str_get(&line));
    dm_str_cat(out, "\n");
    dm_str_free(&line);
}

/* One block: the label column and columns [from, to); the notes in the
 * first block. */
static void table__block(const dm_table *t, const size_t *w, size_t from, size_t to, const char *indent,
                         size_t width, dm_str *out)
{
    for (size_t r = 0; r < t->n_rows; r++) {
        dm_str line = {0};
        dm_str_cat(&line, indent);
        const char *label = table__cell(t, r, 0);
        dm_str_cat(&line, label);
        table__pad(&line, w[0] - dm_text_width(label));
        for (size_t c = from; c < to; c++) {
            const char *v = table__cell(t, r, c);
            int left = c < t->n_left;
            table__pad(&line, left ? 2 : 2 + w[c] - dm_text_width(v));
            dm_str_cat(&line, v);
            if (left)
                table__pad(&line, w[c] - dm_text_width(v));
        }
        while (line.len && line.buf[line.len - 1] == ' ')   /* no trailing blanks */
            line.buf[--line.len] = '\0';
        dm_str_cat(out, dm_str_get(&line));
        dm_str_cat(out, "\n");
        dm_str_free(&line);
        if (from == 1 && t->notes[r]) {
            dm_str pad = {0};
            dm_str_cat(&pad, indent);
            table__pad(&pad, w[0] + 2);
            dm_wrap(t->notes[r], dm_str_get(&pad), dm_str_get(&pad), width, out);
            dm_str_free(&pad);
        }
        if (r == 0) {   /* the rule under the header */
            size_t total = w[0];
            for (size_t c = from; c < to; c++)
                total += 2 + w[c];
            dm_str_cat(out, indent);
            for (size_t i = 0; i < total; i++)
                dm_str_cat(out, "-");
            dm_str_cat(out, "\n");
        }
    }
}

void dm_table_text(const dm_table *t, const char *indent, size_t width, dm_str *out)
{
    size_t nc = 0;
    for (size_t r = 0; r < t->n_rows; r++)
        nc = t->n_cells[r] > nc ? t->n_cells[r] : nc;
    if (!nc)
        return;
    size_t *w = dm_xcalloc(nc, sizeof *w);
    for (size_t r = 0; r < t->n_rows; r++)
        for (size_t c = 0; c < t->n_cells[r]; c++) {
            size_t cw = dm_text_width(t->rows[r][c]);
            w[c] = cw > w[c] ? cw : w[c];
        }
    size_t from = 1, avail = width > dm_text_width(indent) ? width - dm_text_width(indent) : 0;
    do {   /* as many value columns as fit beside the label, at least one */
        size_t to = from, used = w[0];
        while (to < nc && (to == from || used + 2 + w[to] <= avail))
            used += 2 + w[to++];
        if (from > 1)
            dm_str_cat(out, "\n");
        table__block(t, w, from, to, indent, width, out);
        from = to;
    } while (from < nc);
    free(w);
}

void dm_str_cat_count(dm_str *s, double v)
{
    if (!isfinite(v)) {
        dm_str_cat(s, "–");
        return;
    }
    char digits[64];
    double a = fabs(v) < 1e18 ? round(fabs(v)) : fabs(v);
    snprintf(digits, sizeof digits, "%.0f", a);
    size_t n = strlen(digits);
    if (v < 0 && a > 0)
        dm_str_cat(s, "−");
    for (size_t i = 0; i < n; i++) {
        if (n >= 4 && i && (n - i) % 3 == 0)
            dm_str_cat(s, "\u202f");
        dm_str_catn(s, digits + i, 1);
    }
}
