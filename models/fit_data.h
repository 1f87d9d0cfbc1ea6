/* fit_data.h — numeric tables for `dmbench fit --data FILE.csv`.
 *
 * CSV format (RFC 4180, so dmbench's own results.csv reads as it is): a
 * header row of column names, then records separated by commas; a field in
 * double quotes may hold commas, line breaks and "" for a quote.  Unquoted
 * cells are trimmed; an empty cell is a missing value (NaN, the fit excludes
 * its row); "nan"/"inf" are accepted as strtod reads them.  A column whose
 * first non-empty cell is not a number is a text column (key, scene,
 * technique, ...): all NaN, so a formula cannot use it; a later non-number in
 * a numeric column is an error.  Blank lines are skipped; CRLF or LF.
 */
#ifndef MODELS_FIT_DATA_H
#define MODELS_FIT_DATA_H

#include <stddef.h>
#include "core/dm_util.h"
#include "models/fit.h"

typedef struct fit_data {
    char **names;            /* n_cols column names */
    size_t n_cols;
    double *values;          /* n_rows x n_cols, row-major */
    size_t n_rows, cap;      /* rows read, rows allocated */
    unsigned char *text;     /* per column: 0 no value yet, 1 text, 2 numbers */
    double *y;               /* response column, filled by fit_data_desc */
} fit_data;

/* Loads a CSV file.  Returns 0, DM_ERR_IO (unreadable) or DM_ERR_PARSE with
 * a message "FILE:LINE:COLUMN: ..." (1-based) for a bad cell, a wrong cell
 * count or an empty/duplicate header name; *out is zeroed on failure. */
int fit_data_load_csv(const char *path, fit_data *out, dm_str *err);
void fit_data_free(fit_data *d);

/* Fills desc (zeroed first) to fit `formula` to column `response`: every
 * column is a variable (so the response name is data if a formula uses it),
 * y is a copy of the response column kept in d.  desc borrows from d.
 * Returns 0 or DM_ERR_UNKNOWN (no such column; the message lists them). */
int fit_data_desc(fit_data *d, const char *formula, const char *response, fit_desc *desc,
                  dm_str *err);

#endif
