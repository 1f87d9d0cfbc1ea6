/* store_history.c — a configuration's WallTime across runs (store_history.h).
 * Read-only queries over the schema of store.c. */
#include "store/store_history.h"

#include "core/dm_error.h"

#include <math.h>
#include <sqlite3.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const char *const history_sql =
    "SELECT r.id, r.started, w.median, w.ci_lo, w.ci_hi, s.data,"
    " (SELECT CASE WHEN i.has_samples THEN i.median ELSE i.value END FROM counters i"
    "   WHERE i.run = c.run AND i.key = c.key AND i.name = 'Instructions' AND i.available)"
    " FROM configs c JOIN runs r ON r.id = c.run"
    " JOIN counters w ON w.run = c.run AND w.key = c.key AND w.name = 'WallTime'"
    " LEFT JOIN samples s ON s.run = c.run AND s.key = c.key AND s.counter = 'WallTime'"
    " WHERE c.key = ?1 AND c.status = 'ok' AND w.available AND w.has_samples"
    " AND (?2 IS NULL OR EXISTS (SELECT 1 FROM run_env e WHERE e.run = r.id"
    "      AND e.key = 'fingerprint' AND e.value = ?2))"
    " ORDER BY r.started, r.rowid";

/* A REAL column; NULL (the store's NaN) reads as NaN. */
static double history__real(sqlite3_stmt *st, int i)
{
    return sqlite3_column_type(st, i) == SQLITE_NULL ? NAN : sqlite3_column_double(st, i);
}

/* Column i, a blob of little-endian doubles, into p->samples. */
static void history__samples(sqlite3_stmt *st, int i, store_history_point *p)
{
    const unsigned char *b = sqlite3_column_blob(st, i);
    size_t n = (size_t)sqlite3_column_bytes(st, i) / 8;
    p->samples = dm_xmalloc((n + 1) * sizeof *p->samples);
    for (size_t k = 0; b && k < n; k++) {
        uint64_t u = 0;
        for (int j = 0; j < 8; j++)
            u |= (uint64_t)b[k * 8 + (size_t)j] << (8 * j);
        memcpy(&p->samples[k], &u, 8);
    }
    p->n_samples = b ? n : 0;
}

int store_history(store *s, const char *key, const char *fingerprint,
                  store_history_point **out, size_t *n)
{
    sqlite3_stmt *st = NULL;
    size_t cap = 0;
    *out = NULL;
    *n = 0;
    if (sqlite3_prepare_v2(store__db(s), history_sql, -1, &st, NULL) != SQLITE_OK)
        return DM_ERR_STORE;
    sqlite3_bind_text(st, 1, key, -1, SQLITE_TRANSIENT);
    if (fingerprint)
        sqlite3_bind_text(st, 2, fingerprint, -1, SQLITE_TRANSIENT);
    int rc;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        if (*n == cap)
            *out = dm_xrealloc(*out, (cap = cap * 2 + 8) * sizeof **out);
        store_history_point *p = &(*out)[(*n)++];
        p->run_id = dm_xstrdup((const char *)sqlite3_column_text(st, 0));
        p->started = dm_xstrdup((const char *)sqlite3_column_text(st, 1));
        p->median = history__real(st, 2);
        p->ci_lo = history__real(st, 3);
        p->ci_hi = history__real(st, 4);
        history__samples(st, 5, p);
        p->instructions = history__real(st, 6);
    }
    sqlite3_finalize(st);
    if (rc != SQLITE_DONE) {
        store_history_free(*out, *n);
        *out = NULL;
        *n = 0;
        return DM_ERR_STORE;
    }
    return 0;
}

void store_history_free(store_history_point *p, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        free(p[i].run_id);
        free(p[i].started);
        free(p[i].samples);
    }
    free(p);
}

int store_run_fingerprint(store *s, const char *run_id, char **fp)
{
    sqlite3_stmt *st = NULL;
    *fp = NULL;
    if (sqlite3_prepare_v2(store__db(s),
                           "SELECT (SELECT value FROM run_env WHERE run = r.id AND key = 'fingerprint')"
                           " FROM runs r WHERE r.id = ?1", -1, &st, NULL) != SQLITE_OK)
        return DM_ERR_STORE;
    sqlite3_bind_text(st, 1, run_id, -1, SQLITE_TRANSIENT);
    int rc = sqlite3_step(st);
    if (rc == SQLITE_ROW && sqlite3_column_type(st, 0) != SQLITE_NULL)
        *fp = dm_xstrdup((const char *)sqlite3_column_text(st, 0));
    sqlite3_finalize(st);
    return rc == SQLITE_ROW ? 0 : rc == SQLITE_DONE ? DM_ERR_NOTFOUND : DM_ERR_STORE;
}
