/* dm_table.h — a plain-text table for the terminal that fits a width.
 *
 * Cells are UTF-8 text; the first column is the row's label (left-aligned,
 * with the next n_left - 1), the others are values (right-aligned).  A table wider than the width is
 * written as several tables, each repeating the label column, so no line
 * runs past it (a label or a cell wider than the width alone is the one
 * exception: it is never cut).  Usage:
 *
 *   dm_table t = {0};
 *   dm_table_row(&t);  dm_table_cell(&t, "configuration"); dm_table_cell(&t, "VSInvocations");
 *   dm_table_row(&t);  dm_table_cell(&t, "pom steps=8");   dm_table_cell(&t, "4");
 *   dm_table_text(&t, "  ", 100, &out);   // the first row is the header
 *   dm_table_free(&t);
 */
#ifndef CORE_DM_TABLE_H
#define CORE_DM_TABLE_H

#include "dm_util.h"

#include <stddef.h>

typedef struct dm_table {
    char ***rows;     /* rows[r][c], malloc'd */
    size_t *n_cells;  /* cells of each row */
    char **notes;     /* notes[r]: text under row r, or NULL */
    size_t n_rows;
    size_t n_left;    /* leading columns aligned left (0: the label column alone) */
} dm_table;

/* Starts a new row; cells are appended to the last row. */
void dm_table_row(dm_table *t);
/* Appends a copy of text (NULL: "") to the last row (a row is started when
 * there is none). */
void dm_table_cell(dm_table *t, const char *text);
/* Appends the table to out: row 0 is the header, followed by a rule of '-';
 * each line starts with indent and is at most width display columns (see
 * above).  Rows with fewer cells leave the rest blank. */
/* Sets the note of the last row: text written under it (in the first block
 * only), from the second column on, word-wrapped to the width. */
void dm_table_note(dm_table *t, const char *text);
void dm_table_text(const dm_table *t, const char *indent, size_t width, dm_str *out);
void dm_table_free(dm_table *t);

/* Appends text word-wrapped to width display columns: the first line
 * starts with first, the others with indent; a word longer than a line is
 * never cut.  Ends with a newline. */
void dm_wrap(const char *text, const char *first, const char *indent, size_t width, dm_str *out);

/* Display columns of UTF-8 text on a terminal: one per code point (the
 * tool's labels use no wide characters). */
size_t dm_text_width(const char *text);

/* v rounded to an integer in plain digits, grouped by three with U+202F
 * (narrow no-break space) from 1 000 up ("640", "6 144", "3 169 024"), with
 * "−" when negative; "–" when not finite. */
void dm_str_cat_count(dm_str *s, double v);

#endif
