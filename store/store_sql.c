/* store_sql.c — the results store's statements (store_sql.h): prepared once,
 * bound by kind letters, stepped, and their errors recorded on the handle.
 *
 * Statements are prepared once per handle (SQLITE_PREPARE_PERSISTENT) from
 * the STORE_SQL list.  Child statements all take the owner as ?1 run, ?2
 * configuration key, ?3 seq (each uses the ones it needs) and their payload
 * from ?4, so one helper writes and reads every key/value and text list.
 *
 * Raw samples (and a fit's measured/predicted points) are one BLOB per
 * counter: n little-endian IEEE-754 doubles, 8 bytes each.  A row per sample
 * would cost an insert per frame and several times the space; the blob keeps
 * every bit, NaN payloads included.
 *
 * Non-finite doubles in REAL columns: SQLite stores ±Inf as REAL exactly but
 * turns NaN into NULL.  No double of the model is optional, so a NULL in a
 * REAL column always means NaN and is read back as NaN.
 */
#include "store/store_sql.h"
#include "core/dm_error.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const char *const store_sql__text[STORE_SQL_COUNT] = {
#define STORE__TEXT(name, sql) sql,
    STORE_SQL(STORE__TEXT)
#undef STORE__TEXT
};

/* ---- errors -------------------------------------------------------------- */

/* Replaces the last error with "path: <formatted>" and returns code. */
int store_sql_failf(store *s, int code, const char *fmt, ...)
{
    va_list ap;
    s->err.len = 0;
    if (s->err.buf)
        s->err.buf[0] = '\0';
    dm_str_printf(&s->err, "%s: ", s->path);
    va_start(ap, fmt);
    dm_str_vprintf(&s->err, fmt, ap);
    va_end(ap);
    return code;
}

/* Records SQLite's current message for what was being done; DM_ERR_STORE. */
int store_sql_fail(store *s, const char *what)
{
    int code = sqlite3_extended_errcode(s->db), prim = code & 0xff;
    if (prim == SQLITE_CORRUPT || prim == SQLITE_NOTADB)   /* say what to do, not only what broke */
        return store_sql_failf(s, DM_ERR_STORE, "the results store is damaged (%s: %s, SQLite code "
                            "%d); restore dmbench.sqlite from a backup, or give another --out",
                            what, sqlite3_errmsg(s->db), code);
    int os = sqlite3_system_errno(s->db);   /* the file system's reason: "File too large" */
    if (os && (prim == SQLITE_IOERR || prim == SQLITE_FULL || prim == SQLITE_CANTOPEN))
        return store_sql_failf(s, DM_ERR_STORE, "%s: %s (%s; SQLite code %d)", what, sqlite3_errmsg(s->db),
                            strerror(os), code);
    return store_sql_failf(s, DM_ERR_STORE, "%s: %s (SQLite code %d)", what, sqlite3_errmsg(s->db),
                        code);
}

const char *store_last_error(const store *s)
{
    return s ? dm_str_get(&s->err) : "";
}

struct sqlite3 *store__db(store *s)
{
    return s->db;
}

/* ---- doubles: blobs and NaN ------------------------------------------------ */

/* n doubles as little-endian bytes (malloc'd, at least 1 byte). */
static unsigned char *store_sql__pack(const double *v, size_t n)
{
    unsigned char *buf = dm_xmalloc(n * 8 + 1);
    for (size_t i = 0; i < n; i++) {
        uint64_t u;
        memcpy(&u, &v[i], 8);
        for (int b = 0; b < 8; b++)
            buf[i * 8 + (size_t)b] = (unsigned char)(u >> (8 * b));
    }
    return buf;
}

/* Column i as a malloc'd array of doubles (NULL for a NULL column). */
double *store_sql_col_doubles(sqlite3_stmt *st, int i, size_t *n)
{
    const unsigned char *p = sqlite3_column_blob(st, i);
    size_t bytes = (size_t)sqlite3_column_bytes(st, i);
    *n = 0;
    if (sqlite3_column_type(st, i) == SQLITE_NULL)
        return NULL;
    double *v = dm_xmalloc((bytes / 8 + 1) * sizeof *v);
    for (size_t k = 0; k < bytes / 8; k++) {
        uint64_t u = 0;
        for (int b = 0; b < 8; b++)
            u |= (uint64_t)p[k * 8 + (size_t)b] << (8 * b);
        memcpy(&v[k], &u, 8);
    }
    *n = bytes / 8;
    return v;
}

double store_sql_col_double(sqlite3_stmt *st, int i)
{
    if (sqlite3_column_type(st, i) == SQLITE_NULL)
        return NAN;
    return sqlite3_column_double(st, i);
}

char *store_sql_col_str(sqlite3_stmt *st, int i)
{
    return dm_xstrdup((const char *)sqlite3_column_text(st, i));
}

/* ---- statements ------------------------------------------------------------ */

/* Binds one argument of kind k from ap to parameter i.  Kinds: t text (NULL
 * ok), i int, l long, d double (NaN stored as NULL), b doubles (const double
 * *, size_t n) as a blob, NULL pointer → NULL. */
static int store_sql__bind(sqlite3_stmt *st, int i, char k, va_list *ap)
{
    if (k == 't')
        return sqlite3_bind_text(st, i, va_arg(*ap, const char *), -1,
                                 SQLITE_TRANSIENT);
    if (k == 'i')
        return sqlite3_bind_int(st, i, va_arg(*ap, int));
    if (k == 'l')
        return sqlite3_bind_int64(st, i, va_arg(*ap, long));
    if (k == 'd') {
        double d = va_arg(*ap, double);
        return isnan(d) ? sqlite3_bind_null(st, i) : sqlite3_bind_double(st, i, d);
    }
    const double *v = va_arg(*ap, const double *);
    size_t n = va_arg(*ap, size_t);
    if (!v)
        return sqlite3_bind_null(st, i);
    return sqlite3_bind_blob64(st, i, store_sql__pack(v, n), n * 8, free);
}

/* Binds owner o (NULL: none) to the owner slots ?1..?3 the statement has. */
static int store_sql__bind_owner(sqlite3_stmt *st, const store_sql_owner *o)
{
    int n = sqlite3_bind_parameter_count(st), rc = SQLITE_OK;
    if (o && n >= 1)
        rc = sqlite3_bind_text(st, 1, o->run, -1, SQLITE_TRANSIENT);
    if (o && n >= 2 && rc == SQLITE_OK)
        rc = sqlite3_bind_text(st, 2, o->key, -1, SQLITE_TRANSIENT);
    if (o && n >= 3 && rc == SQLITE_OK)
        rc = sqlite3_bind_int64(st, 3, o->seq);
    return rc;
}

/* The cached statement id, reset, with owner o in ?1..?3 and the payload
 * from ?4, one kind of fmt per parameter; NULL with the error recorded on
 * failure.  A payload that does not match the statement's parameters is
 * refused (DM_ERR_MISUSE), so a miscounted format never binds garbage. */
static sqlite3_stmt *store_sql__vprep(store *s, enum store_sql id, const store_sql_owner *o,
                                  const char *fmt, va_list ap)
{
    sqlite3_stmt **st = &s->st[id];
    if (!*st && sqlite3_prepare_v3(s->db, store_sql__text[id], -1,
                                   SQLITE_PREPARE_PERSISTENT, st, NULL)) {
        store_sql_fail(s, "preparing a statement");
        return NULL;
    }
    sqlite3_reset(*st);
    sqlite3_clear_bindings(*st);
    int count = sqlite3_bind_parameter_count(*st), len = (int)strlen(fmt);
    if (len ? count != 3 + len : count > 3) {
        store_sql_failf(s, DM_ERR_MISUSE, "statement %d takes %d parameters, "
                     "given 3 + %d", (int)id, count, len);
        return NULL;
    }
    int rc = store_sql__bind_owner(*st, o);
    va_list aq;
    va_copy(aq, ap);
    for (int i = 0; fmt[i] && rc == SQLITE_OK; i++)
        rc = store_sql__bind(*st, 4 + i, fmt[i], &aq);
    va_end(aq);
    if (rc != SQLITE_OK) {
        store_sql_fail(s, "binding a value");
        return NULL;
    }
    return *st;
}

sqlite3_stmt *store_sql_query(store *s, enum store_sql id,
                                  const store_sql_owner *o, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sqlite3_stmt *st = store_sql__vprep(s, id, o, fmt, ap);
    va_end(ap);
    return st;
}

/* Steps a prepared query: 1 with a row, 0 at the end (statement reset),
 * DM_ERR_STORE on failure (statement reset). */
int store_sql_row(store *s, sqlite3_stmt *st)
{
    int rc = sqlite3_step(st);
    if (rc == SQLITE_ROW)
        return 1;
    int ret = rc == SQLITE_DONE ? 0 : store_sql_fail(s, "executing a statement");
    sqlite3_reset(st);
    sqlite3_clear_bindings(st);
    return ret;
}

/* Runs a statement for its effect (a row it may return is ignored). */
int store_sql_exec(store *s, enum store_sql id, const store_sql_owner *o,
                       const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sqlite3_stmt *st = store_sql__vprep(s, id, o, fmt, ap);
    va_end(ap);
    if (!st)
        return DM_ERR_STORE;
    int rc = store_sql_row(s, st);
    if (rc == 1) {
        sqlite3_reset(st);
        rc = 0;
    }
    return rc;
}

/* Runs a one-integer query into *v; DM_ERR_NOTFOUND when it returns no row. */
int store_sql_scalar(store *s, long *v, enum store_sql id,
                         const store_sql_owner *o, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sqlite3_stmt *st = store_sql__vprep(s, id, o, fmt, ap);
    va_end(ap);
    int rc = st ? store_sql_row(s, st) : DM_ERR_STORE;
    if (rc == 1) {
        *v = (long)sqlite3_column_int64(st, 0);
        sqlite3_reset(st);
        return 0;
    }
    return rc < 0 ? rc : DM_ERR_NOTFOUND;
}
