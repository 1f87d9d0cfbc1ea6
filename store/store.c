/* store.c — the results store on SQLite.
 *
 * Schema (version 4, kept in PRAGMA user_version; store__migrations[i] takes a
 * database from version i to i+1).  Everything hangs off a run and is
 * deleted with it (ON DELETE CASCADE); order is kept by seq columns and by
 * rowid for lists:
 *
 *   runs(id PK, sweep, started, finished, sweep_hash, gpu_time_coverage,
 *        timer_verdict, tag)
 *   run_env(run, key, value)                 environment, insertion order
 *   run_warnings(run, text)
 *   configs(run, key, seq, scene, status 'ok'|'failed', reason, log,
 *           q_present, q_rmse, q_psnr, q_ssim, q_max_error, q_pct_over,
 *           q_silhouette, q_depth_rmse, q_crack_pixels, q_nonfinite_pixels,
 *           q_reference, img_render, img_heatmap, img_reference,
 *           q_flip, q_flip_q1, q_flip_median, q_flip_q3, q_flip_max,
 *           q_flip_ppd, img_flip (version 4))
 *           PK (run, key); seq is the insertion position, kept on replace
 *   config_params(run, key, name, value)     → configs
 *   counters(run, key, name, unit, available, unavailable_reason,
 *            deterministic, partial, value, has_samples, median, mean, min,
 *            max, stddev, mad, cv, ci_lo, ci_hi, n_outliers, n_nonfinite)
 *            PK (run, key, name)             → configs
 *   samples(run, key, counter, data BLOB)    → counters
 *   partial_samples(run, key, counter, data BLOB, sampling_ns)  PK (run,
 *           key, counter): timing samples of a configuration still being
 *           measured, checkpointed after every round so a kill loses at most
 *           the round in flight; deleted when the configuration is stored
 *           (version 3)
 *   left_out(run, seq, reason), left_out_params(run, seq, name, value)
 *   fits(run, seq, model, group_key, formula, response, r2, rmse, mape,
 *        cv_mape, n_points, n_excluded, termination, measured BLOB,
 *        predicted BLOB, condition)  PK (run, seq), UNIQUE (run, model,
 *        group_key); condition came with version 2 (a version-1 store gets
 *        the column with 0, "not computed", for its fits)
 *   fit_group(run, seq, key, value), fit_params(run, seq, name, value,
 *        stderr), fit_warnings(run, seq, text), fit_labels(run, seq, idx,
 *        label)
 *
 * Raw samples (and a fit's measured/predicted points) are one BLOB per
 * counter: n little-endian IEEE-754 doubles, 8 bytes each.  A row per sample
 * would cost an insert per frame and several times the space; the blob keeps
 * every bit, NaN payloads included.
 *
 * Non-finite doubles in REAL columns: SQLite stores ±Inf as REAL exactly but
 * turns NaN into NULL.  No double of the model is optional, so a NULL in a
 * REAL column always means NaN and is read back as NaN.
 *
 * Durability: WAL journal with synchronous=FULL.  A configuration takes
 * seconds to measure, so one fsync per commit costs nothing measurable, and
 * with FULL a committed configuration also survives a power loss (NORMAL
 * only survives a process crash).  Every write goes through store__tx(): one
 * BEGIN IMMEDIATE … COMMIT, rolled back on any failure.
 *
 * Statements are prepared once per handle (SQLITE_PREPARE_PERSISTENT) from
 * the STORE_SQL list.  Child statements all take the owner as ?1 run, ?2
 * configuration key, ?3 seq (each uses the ones it needs) and their payload
 * from ?4, so one helper writes and reads every key/value and text list.
 */
#include "store/store.h"
#include "core/dm_error.h"

#include <sqlite3.h>

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define STORE_SCHEMA_VERSION 4
#define STORE__XSTR(x) #x
#define STORE__STR(x) STORE__XSTR(x)

static const char *const store__migrations[STORE_SCHEMA_VERSION] = {
    /* 0 -> 1 */
    "CREATE TABLE runs(id TEXT PRIMARY KEY, sweep TEXT, started TEXT,"
    " finished TEXT, sweep_hash TEXT, gpu_time_coverage REAL,"
    " timer_verdict TEXT, tag TEXT);"
    "CREATE INDEX runs_by_start ON runs(started);"
    "CREATE TABLE run_env(run TEXT NOT NULL REFERENCES runs(id) ON DELETE"
    " CASCADE, key TEXT NOT NULL, value TEXT, PRIMARY KEY(run, key));"
    "CREATE TABLE run_warnings(run TEXT NOT NULL REFERENCES runs(id) ON DELETE"
    " CASCADE, text TEXT);"
    "CREATE INDEX run_warnings_by_run ON run_warnings(run);"
    "CREATE TABLE configs(run TEXT NOT NULL REFERENCES runs(id) ON DELETE"
    " CASCADE, key TEXT NOT NULL, seq INTEGER NOT NULL, scene TEXT,"
    " status TEXT NOT NULL CHECK(status IN ('ok','failed')), reason TEXT,"
    " log TEXT, q_present INTEGER, q_rmse REAL, q_psnr REAL, q_ssim REAL,"
    " q_max_error REAL, q_pct_over REAL, q_silhouette REAL, q_depth_rmse REAL,"
    " q_crack_pixels INTEGER, q_nonfinite_pixels INTEGER, q_reference TEXT,"
    " img_render TEXT, img_heatmap TEXT, img_reference TEXT,"
    " PRIMARY KEY(run, key));"
    "CREATE INDEX configs_by_seq ON configs(run, seq);"
    "CREATE TABLE config_params(run TEXT NOT NULL, key TEXT NOT NULL,"
    " name TEXT NOT NULL, value TEXT, PRIMARY KEY(run, key, name),"
    " FOREIGN KEY(run, key) REFERENCES configs(run, key) ON DELETE CASCADE);"
    "CREATE TABLE counters(run TEXT NOT NULL, key TEXT NOT NULL,"
    " name TEXT NOT NULL, unit TEXT, available INTEGER, unavailable_reason"
    " TEXT, deterministic INTEGER, partial INTEGER, value REAL, has_samples"
    " INTEGER, median REAL, mean REAL, min REAL, max REAL, stddev REAL,"
    " mad REAL, cv REAL, ci_lo REAL, ci_hi REAL, n_outliers INTEGER,"
    " n_nonfinite INTEGER, PRIMARY KEY(run, key, name),"
    " FOREIGN KEY(run, key) REFERENCES configs(run, key) ON DELETE CASCADE);"
    "CREATE TABLE samples(run TEXT NOT NULL, key TEXT NOT NULL,"
    " counter TEXT NOT NULL, data BLOB, PRIMARY KEY(run, key, counter),"
    " FOREIGN KEY(run, key, counter) REFERENCES counters(run, key, name)"
    " ON DELETE CASCADE);"
    "CREATE TABLE left_out(run TEXT NOT NULL REFERENCES runs(id) ON DELETE"
    " CASCADE, seq INTEGER NOT NULL, reason TEXT, PRIMARY KEY(run, seq));"
    "CREATE TABLE left_out_params(run TEXT NOT NULL, seq INTEGER NOT NULL,"
    " name TEXT NOT NULL, value TEXT, PRIMARY KEY(run, seq, name),"
    " FOREIGN KEY(run, seq) REFERENCES left_out(run, seq) ON DELETE CASCADE);"
    "CREATE TABLE fits(run TEXT NOT NULL REFERENCES runs(id) ON DELETE"
    " CASCADE, seq INTEGER NOT NULL, model TEXT NOT NULL, group_key TEXT NOT"
    " NULL, formula TEXT, response TEXT, r2 REAL, rmse REAL, mape REAL,"
    " cv_mape REAL, n_points INTEGER, n_excluded INTEGER, termination TEXT,"
    " measured BLOB, predicted BLOB, PRIMARY KEY(run, seq),"
    " UNIQUE(run, model, group_key));"
    "CREATE TABLE fit_group(run TEXT NOT NULL, seq INTEGER NOT NULL,"
    " key TEXT NOT NULL, value TEXT, PRIMARY KEY(run, seq, key),"
    " FOREIGN KEY(run, seq) REFERENCES fits(run, seq) ON DELETE CASCADE);"
    "CREATE TABLE fit_params(run TEXT NOT NULL, seq INTEGER NOT NULL,"
    " name TEXT NOT NULL, value REAL, stderr REAL, PRIMARY KEY(run, seq, name),"
    " FOREIGN KEY(run, seq) REFERENCES fits(run, seq) ON DELETE CASCADE);"
    "CREATE TABLE fit_warnings(run TEXT NOT NULL, seq INTEGER NOT NULL,"
    " text TEXT, FOREIGN KEY(run, seq) REFERENCES fits(run, seq) ON DELETE"
    " CASCADE);"
    "CREATE INDEX fit_warnings_by_fit ON fit_warnings(run, seq);"
    "CREATE TABLE fit_labels(run TEXT NOT NULL, seq INTEGER NOT NULL,"
    " idx INTEGER NOT NULL, label TEXT, PRIMARY KEY(run, seq, idx),"
    " FOREIGN KEY(run, seq) REFERENCES fits(run, seq) ON DELETE CASCADE);",
    /* 1 -> 2: a fit's condition number (0 = not computed) */
    "ALTER TABLE fits ADD COLUMN condition REAL DEFAULT 0;",
    /* 2 -> 3: timing samples of configurations not finished yet */
    "CREATE TABLE partial_samples(run TEXT NOT NULL REFERENCES runs(id) ON DELETE"
    " CASCADE, key TEXT NOT NULL, counter TEXT NOT NULL, data BLOB,"
    " sampling_ns INTEGER, PRIMARY KEY(run, key, counter));",
    /* 3 -> 4: LDR-FLIP (imaging/flip.h) and its error map; NULL before */
    "ALTER TABLE configs ADD COLUMN q_flip REAL;"
    "ALTER TABLE configs ADD COLUMN q_flip_q1 REAL;"
    "ALTER TABLE configs ADD COLUMN q_flip_median REAL;"
    "ALTER TABLE configs ADD COLUMN q_flip_q3 REAL;"
    "ALTER TABLE configs ADD COLUMN q_flip_max REAL;"
    "ALTER TABLE configs ADD COLUMN q_flip_ppd REAL;"
    "ALTER TABLE configs ADD COLUMN img_flip TEXT;",
};

#define STORE__CFG_COLS "scene,status,reason,log,q_present,q_rmse,q_psnr," \
    "q_ssim,q_max_error,q_pct_over,q_silhouette,q_depth_rmse,q_crack_pixels," \
    "q_nonfinite_pixels,q_reference,img_render,img_heatmap,img_reference," \
    "q_flip,q_flip_q1,q_flip_median,q_flip_q3,q_flip_max,q_flip_ppd,img_flip"
#define STORE__CTR_COLS "unit,available,unavailable_reason,deterministic," \
    "partial,value,has_samples,median,mean,min,max,stddev,mad,cv,ci_lo," \
    "ci_hi,n_outliers,n_nonfinite"
#define STORE__FIT_COLS "formula,response,r2,rmse,mape,cv_mape,n_points," \
    "n_excluded,termination,measured,predicted,condition"

/* Owner parameters: ?1 run, ?2 config key, ?3 seq; payload from ?4. */
#define STORE_SQL(X)                                                          \
    X(BEGIN_WRITE, "BEGIN IMMEDIATE")                                         \
    X(BEGIN_READ, "BEGIN")                                                    \
    X(COMMIT, "COMMIT")                                                       \
    X(ROLLBACK, "ROLLBACK")                                                   \
    X(RUN_EXISTS, "SELECT 1 FROM runs WHERE id=?1")                           \
    X(RUN_INS, "INSERT INTO runs(id,sweep,started,finished,sweep_hash,"       \
      "gpu_time_coverage,timer_verdict,tag) VALUES(?1,?4,?5,?6,?7,?8,?9,?10)")\
    X(RUN_SEL, "SELECT sweep,started,finished,sweep_hash,gpu_time_coverage,"  \
      "timer_verdict FROM runs WHERE id=?1")                                  \
    X(RUN_TAG, "SELECT tag FROM runs WHERE id=?1")                            \
    X(RUN_FINISH, "UPDATE runs SET finished=?4 WHERE id=?1")                  \
    X(RUN_LIST, "SELECT id FROM runs WHERE ?4 IS NULL OR tag=?4"              \
      " ORDER BY started DESC, rowid DESC")                                   \
    X(ENV_INS, "INSERT INTO run_env(run,key,value) VALUES(?1,?4,?5)")         \
    X(ENV_SEL, "SELECT key,value FROM run_env WHERE run=?1 ORDER BY rowid")   \
    X(RWARN_INS, "INSERT INTO run_warnings(run,text) VALUES(?1,?4)")          \
    X(RWARN_SEL, "SELECT text FROM run_warnings WHERE run=?1 ORDER BY rowid") \
    X(CFG_SEQ, "SELECT COALESCE((SELECT seq FROM configs WHERE run=?1 AND"    \
      " key=?2),(SELECT IFNULL(MAX(seq),0)+1 FROM configs WHERE run=?1))")    \
    X(CFG_DEL, "DELETE FROM configs WHERE run=?1 AND key=?2")                 \
    X(CFG_INS, "INSERT INTO configs(run,key,seq," STORE__CFG_COLS ") VALUES"  \
      "(?1,?2,?3,?4,?5,?6,?7,?8,?9,?10,?11,?12,?13,?14,?15,?16,?17,?18,?19,"  \
      "?20,?21,?22,?23,?24,?25,?26,?27,?28)")                                                             \
    X(CFG_SEL, "SELECT key," STORE__CFG_COLS " FROM configs WHERE run=?1"     \
      " ORDER BY seq")                                                        \
    X(CFG_DONE, "SELECT 1 FROM configs WHERE run=?1 AND key=?2")              \
    X(CPAR_INS, "INSERT INTO config_params(run,key,name,value)"               \
      " VALUES(?1,?2,?4,?5)")                                                 \
    X(CPAR_SEL, "SELECT name,value FROM config_params WHERE run=?1 AND"       \
      " key=?2 ORDER BY rowid")                                               \
    X(CTR_INS, "INSERT INTO counters(run,key,name," STORE__CTR_COLS ") VALUES"\
      "(?1,?2,?4,?5,?6,?7,?8,?9,?10,?11,?12,?13,?14,?15,?16,?17,?18,?19,?20," \
      "?21,?22)")                                                             \
    X(CTR_SEL, "SELECT name," STORE__CTR_COLS " FROM counters WHERE run=?1"   \
      " AND key=?2 ORDER BY rowid")                                           \
    X(SMP_INS, "INSERT INTO samples(run,key,counter,data) VALUES(?1,?2,?4,?5)")\
    X(SMP_SEL, "SELECT data FROM samples WHERE run=?1 AND key=?2 AND"         \
      " counter=?4")                                                          \
    X(PART_DEL, "DELETE FROM partial_samples WHERE run=?1 AND key=?2")        \
    X(PART_INS, "INSERT INTO partial_samples(run,key,counter,data,"           \
      "sampling_ns) VALUES(?1,?2,?4,?5,?6)")                                  \
    X(PART_SEL, "SELECT data,sampling_ns FROM partial_samples WHERE run=?1"   \
      " AND key=?2 AND counter=?4")                                           \
    X(LO_SEQ, "SELECT IFNULL(MAX(seq),0)+1 FROM left_out WHERE run=?1")       \
    X(LO_INS, "INSERT INTO left_out(run,seq,reason) VALUES(?1,?3,?4)")        \
    X(LO_SEL, "SELECT seq,reason FROM left_out WHERE run=?1 ORDER BY seq")    \
    X(LOPAR_INS, "INSERT INTO left_out_params(run,seq,name,value)"            \
      " VALUES(?1,?3,?4,?5)")                                                 \
    X(LOPAR_SEL, "SELECT name,value FROM left_out_params WHERE run=?1 AND"    \
      " seq=?3 ORDER BY rowid")                                               \
    X(FIT_SEQ, "SELECT COALESCE((SELECT seq FROM fits WHERE run=?1 AND"       \
      " model=?4 AND group_key=?5),"                                          \
      "(SELECT IFNULL(MAX(seq),0)+1 FROM fits WHERE run=?1))")                \
    X(FIT_DEL, "DELETE FROM fits WHERE run=?1 AND seq=?3")                    \
    X(FIT_INS, "INSERT INTO fits(run,seq,model,group_key," STORE__FIT_COLS    \
      ") VALUES(?1,?3,?4,?5,?6,?7,?8,?9,?10,?11,?12,?13,?14,?15,?16,?17)")    \
    X(FIT_SEL, "SELECT seq,model," STORE__FIT_COLS " FROM fits WHERE run=?1"  \
      " ORDER BY seq")                                                        \
    X(FGRP_INS, "INSERT INTO fit_group(run,seq,key,value) VALUES(?1,?3,?4,?5)")\
    X(FGRP_SEL, "SELECT key,value FROM fit_group WHERE run=?1 AND seq=?3"     \
      " ORDER BY rowid")                                                      \
    X(FPAR_INS, "INSERT INTO fit_params(run,seq,name,value,stderr)"           \
      " VALUES(?1,?3,?4,?5,?6)")                                              \
    X(FPAR_SEL, "SELECT name,value,stderr FROM fit_params WHERE run=?1 AND"   \
      " seq=?3 ORDER BY rowid")                                               \
    X(FWARN_INS, "INSERT INTO fit_warnings(run,seq,text) VALUES(?1,?3,?4)")   \
    X(FWARN_SEL, "SELECT text FROM fit_warnings WHERE run=?1 AND seq=?3"      \
      " ORDER BY rowid")                                                      \
    X(FLBL_INS, "INSERT INTO fit_labels(run,seq,idx,label)"                   \
      " VALUES(?1,?3,?4,?5)")                                                 \
    X(FLBL_SEL, "SELECT idx,label FROM fit_labels WHERE run=?1 AND seq=?3")

enum store_sql {
#define STORE__ENUM(name, sql) STORE_SQL_##name,
    STORE_SQL(STORE__ENUM)
#undef STORE__ENUM
    STORE_SQL_COUNT
};

static const char *const store__sql_text[STORE_SQL_COUNT] = {
#define STORE__TEXT(name, sql) sql,
    STORE_SQL(STORE__TEXT)
#undef STORE__TEXT
};

struct store {
    sqlite3 *db;
    char *path;
    dm_str err;
    sqlite3_stmt *st[STORE_SQL_COUNT];
};

/* Who a child row belongs to: bound as ?1, ?2, ?3 of every statement. */
typedef struct store__owner {
    const char *run;
    const char *key;
    long seq;
} store__owner;

/* ---- errors -------------------------------------------------------------- */

/* Replaces the last error with "path: <formatted>" and returns code. */
static int store__failf(store *s, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int store__failf(store *s, int code, const char *fmt, ...)
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
static int store__fail(store *s, const char *what)
{
    int code = sqlite3_extended_errcode(s->db), prim = code & 0xff;
    if (prim == SQLITE_CORRUPT || prim == SQLITE_NOTADB)   /* say what to do, not only what broke */
        return store__failf(s, DM_ERR_STORE, "the results store is damaged (%s: %s, SQLite code "
                            "%d); restore dmbench.sqlite from a backup, or give another --out",
                            what, sqlite3_errmsg(s->db), code);
    int os = sqlite3_system_errno(s->db);   /* the file system's reason: "File too large" */
    if (os && (prim == SQLITE_IOERR || prim == SQLITE_FULL || prim == SQLITE_CANTOPEN))
        return store__failf(s, DM_ERR_STORE, "%s: %s (%s; SQLite code %d)", what, sqlite3_errmsg(s->db),
                            strerror(os), code);
    return store__failf(s, DM_ERR_STORE, "%s: %s (SQLite code %d)", what, sqlite3_errmsg(s->db),
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
static unsigned char *store__pack(const double *v, size_t n)
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
static double *store__col_doubles(sqlite3_stmt *st, int i, size_t *n)
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

static double store__col_double(sqlite3_stmt *st, int i)
{
    if (sqlite3_column_type(st, i) == SQLITE_NULL)
        return NAN;
    return sqlite3_column_double(st, i);
}

static char *store__col_str(sqlite3_stmt *st, int i)
{
    return dm_xstrdup((const char *)sqlite3_column_text(st, i));
}

/* ---- statements ------------------------------------------------------------ */

/* Binds one argument of kind k from ap to parameter i.  Kinds: t text (NULL
 * ok), i int, l long, d double (NaN stored as NULL), b doubles (const double
 * *, size_t n) as a blob, NULL pointer → NULL. */
static int store__bind(sqlite3_stmt *st, int i, char k, va_list *ap)
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
    return sqlite3_bind_blob64(st, i, store__pack(v, n), n * 8, free);
}

/* Binds owner o (NULL: none) to the owner slots ?1..?3 the statement has. */
static int store__bind_owner(sqlite3_stmt *st, const store__owner *o)
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
static sqlite3_stmt *store__vprep(store *s, enum store_sql id, const store__owner *o,
                                  const char *fmt, va_list ap)
{
    sqlite3_stmt **st = &s->st[id];
    if (!*st && sqlite3_prepare_v3(s->db, store__sql_text[id], -1,
                                   SQLITE_PREPARE_PERSISTENT, st, NULL)) {
        store__fail(s, "preparing a statement");
        return NULL;
    }
    sqlite3_reset(*st);
    sqlite3_clear_bindings(*st);
    int count = sqlite3_bind_parameter_count(*st), len = (int)strlen(fmt);
    if (len ? count != 3 + len : count > 3) {
        store__failf(s, DM_ERR_MISUSE, "statement %d takes %d parameters, "
                     "given 3 + %d", (int)id, count, len);
        return NULL;
    }
    int rc = store__bind_owner(*st, o);
    va_list aq;
    va_copy(aq, ap);
    for (int i = 0; fmt[i] && rc == SQLITE_OK; i++)
        rc = store__bind(*st, 4 + i, fmt[i], &aq);
    va_end(aq);
    if (rc != SQLITE_OK) {
        store__fail(s, "binding a value");
        return NULL;
    }
    return *st;
}

static sqlite3_stmt *store__query(store *s, enum store_sql id,
                                  const store__owner *o, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sqlite3_stmt *st = store__vprep(s, id, o, fmt, ap);
    va_end(ap);
    return st;
}

/* Steps a prepared query: 1 with a row, 0 at the end (statement reset),
 * DM_ERR_STORE on failure (statement reset). */
static int store__row(store *s, sqlite3_stmt *st)
{
    int rc = sqlite3_step(st);
    if (rc == SQLITE_ROW)
        return 1;
    int ret = rc == SQLITE_DONE ? 0 : store__fail(s, "executing a statement");
    sqlite3_reset(st);
    sqlite3_clear_bindings(st);
    return ret;
}

/* Runs a statement for its effect (a row it may return is ignored). */
static int store__exec(store *s, enum store_sql id, const store__owner *o,
                       const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sqlite3_stmt *st = store__vprep(s, id, o, fmt, ap);
    va_end(ap);
    if (!st)
        return DM_ERR_STORE;
    int rc = store__row(s, st);
    if (rc == 1) {
        sqlite3_reset(st);
        rc = 0;
    }
    return rc;
}

/* Runs a one-integer query into *v; DM_ERR_NOTFOUND when it returns no row. */
static int store__scalar(store *s, long *v, enum store_sql id,
                         const store__owner *o, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sqlite3_stmt *st = store__vprep(s, id, o, fmt, ap);
    va_end(ap);
    int rc = st ? store__row(s, st) : DM_ERR_STORE;
    if (rc == 1) {
        *v = (long)sqlite3_column_int64(st, 0);
        sqlite3_reset(st);
        return 0;
    }
    return rc < 0 ? rc : DM_ERR_NOTFOUND;
}

/* ---- transactions ---------------------------------------------------------- */

/* Writes item (of the type its function names) as part of run. */
typedef int (*store__writer)(store *s, const char *run, const void *item);

/* Arguments of one store operation, for store__tx. */
typedef struct store__call {
    const char *run;
    const void *item;
    const char *text;
    void *out;
    store__writer write;   /* for store__put */
} store__call;

typedef int (*store__fn)(store *s, const store__call *c);

/* Runs fn inside one transaction (BEGIN IMMEDIATE when write): commits when
 * fn returns 0, otherwise (or when COMMIT fails) rolls back, keeping fn's
 * error message, so the database is unchanged. */
static int store__tx(store *s, int write, store__fn fn, const store__call *c)
{
    int rc = store__exec(s, write ? STORE_SQL_BEGIN_WRITE : STORE_SQL_BEGIN_READ,
                         NULL, "");
    if (rc < 0)
        return rc;
    rc = fn(s, c);
    if (rc == 0)
        rc = store__exec(s, STORE_SQL_COMMIT, NULL, "");
    if (rc < 0 && !sqlite3_get_autocommit(s->db)) {
        sqlite3_stmt *st = store__query(s, STORE_SQL_ROLLBACK, NULL, "");
        if (st) {
            sqlite3_step(st);
            sqlite3_reset(st);
        }
    }
    return rc;
}

/* 0 if run exists, DM_ERR_NOTFOUND (with a message) if not. */
static int store__need_run(store *s, const char *run)
{
    long one;
    store__owner o = { run, NULL, 0 };
    int rc = store__scalar(s, &one, STORE_SQL_RUN_EXISTS, &o, "");
    if (rc == DM_ERR_NOTFOUND)
        return store__failf(s, rc, "run '%s' is not in the store", run);
    return rc;
}

/* ---- writing (inside a transaction) ------------------------------------------ */

static int store__kv_write(store *s, enum store_sql id, const store__owner *o,
                           const dm_kv *kv, size_t n)
{
    int rc = 0;
    for (size_t i = 0; i < n && rc == 0; i++)
        rc = store__exec(s, id, o, "tt", kv[i].key, kv[i].value);
    return rc;
}

static int store__strv_write(store *s, enum store_sql id, const store__owner *o,
                             char *const *v, size_t n)
{
    int rc = 0;
    for (size_t i = 0; i < n && rc == 0; i++)
        rc = store__exec(s, id, o, "t", v[i]);
    return rc;
}

static int store__counter_write(store *s, const store__owner *o,
                                const dm_counter_result *k)
{
    int rc = store__exec(s, STORE_SQL_CTR_INS, o, "ttitiidi" "ddddddddd" "ii",
        k->name, k->unit, k->available, k->unavailable_reason, k->deterministic,
        k->partial, k->value, k->has_samples,
        k->median, k->mean, k->min, k->max, k->stddev, k->mad, k->cv, k->ci_lo,
        k->ci_hi, k->n_outliers, k->n_nonfinite);
    if (rc == 0 && k->has_samples && k->samples)
        rc = store__exec(s, STORE_SQL_SMP_INS, o, "tb", k->name, k->samples,
                         k->n_samples);
    return rc;
}

static int store__config_row(store *s, const store__owner *o,
                             const dm_config_result *c)
{
    const dm_quality *q = &c->quality;
    return store__exec(s, STORE_SQL_CFG_INS, o, "ttttiddddddd" "lltttt" "ddddddt",
        c->scene, c->ok ? "ok" : "failed", c->reason, c->log, q->present,
        q->rmse, q->psnr, q->ssim, q->max_error, q->pct_over_threshold,
        q->silhouette_error, q->depth_rmse, q->crack_pixels,
        q->nonfinite_pixels, q->reference, c->img_render, c->img_heatmap,
        c->img_reference, q->flip, q->flip_q1, q->flip_median, q->flip_q3,
        q->flip_max, q->flip_ppd, c->img_flip);
}

/* Replaces configuration item (a dm_config_result) of run, keeping its
 * position when it existed. */
static int store__config_write(store *s, const char *run, const void *item)
{
    const dm_config_result *c = item;
    store__owner o = { run, c->key, 0 };
    if (!c->key)
        return store__failf(s, DM_ERR_ARG, "configuration without a key");
    int rc = store__scalar(s, &o.seq, STORE_SQL_CFG_SEQ, &o, "");
    if (rc == 0)
        rc = store__exec(s, STORE_SQL_CFG_DEL, &o, "");
    if (rc == 0)
        rc = store__exec(s, STORE_SQL_PART_DEL, &o, "");
    if (rc == 0)
        rc = store__config_row(s, &o, c);
    if (rc == 0)
        rc = store__kv_write(s, STORE_SQL_CPAR_INS, &o, c->params, c->n_params);
    for (size_t i = 0; i < c->n_counters && rc == 0; i++)
        rc = store__counter_write(s, &o, &c->counters[i]);
    return rc;
}

/* Appends item (a dm_left_out) to the configurations run left out. */
static int store__left_out_write(store *s, const char *run, const void *item)
{
    const dm_left_out *l = item;
    store__owner o = { run, NULL, 0 };
    int rc = store__scalar(s, &o.seq, STORE_SQL_LO_SEQ, &o, "");
    if (rc == 0)
        rc = store__exec(s, STORE_SQL_LO_INS, &o, "t", l->reason);
    if (rc == 0)
        rc = store__kv_write(s, STORE_SQL_LOPAR_INS, &o, l->params, l->n_params);
    return rc;
}

static int store__kv_cmp(const void *a, const void *b)
{
    const dm_kv *x = a, *y = b;
    int c = strcmp(x->key, y->key);
    return c ? c : strcmp(x->value ? x->value : "", y->value ? y->value : "");
}

/* A fit group's identity: its pairs sorted, "key\x1fvalue\x1e" each. */
static char *store__group_key(const dm_kv *kv, size_t n)
{
    dm_kv *sorted = dm_xmalloc((n + 1) * sizeof *sorted);
    if (n)
        memcpy(sorted, kv, n * sizeof *sorted);
    qsort(sorted, n, sizeof *sorted, store__kv_cmp);
    dm_str k = {0};
    for (size_t i = 0; i < n; i++)
        dm_str_printf(&k, "%s\x1f%s\x1e", sorted[i].key,
                      sorted[i].value ? sorted[i].value : "");
    free(sorted);
    return dm_str_take(&k);
}

static int store__fit_children(store *s, const store__owner *o,
                               const dm_fit_result *f)
{
    int rc = store__kv_write(s, STORE_SQL_FGRP_INS, o, f->group, f->n_group);
    for (size_t i = 0; i < f->n_params && rc == 0; i++)
        rc = store__exec(s, STORE_SQL_FPAR_INS, o, "tdd", f->params[i].name,
                         f->params[i].value, f->params[i].stderr_);
    if (rc == 0)
        rc = store__strv_write(s, STORE_SQL_FWARN_INS, o, f->warnings,
                               f->n_warnings);
    for (int i = 0; f->point_labels && i < f->n_points && rc == 0; i++)
        rc = store__exec(s, STORE_SQL_FLBL_INS, o, "it", i, f->point_labels[i]);
    return rc;
}

/* Replaces the fit of the same model and group as item (a dm_fit_result),
 * keeping its position. */
static int store__fit_write(store *s, const char *run, const void *item)
{
    const dm_fit_result *f = item;
    if (!f->model || f->n_points < 0)
        return store__failf(s, DM_ERR_ARG, "fit without a model name or with "
                            "a negative point count");
    size_t np = (size_t)f->n_points;
    char *gk = store__group_key(f->group, f->n_group);
    store__owner o = { run, NULL, 0 };
    int rc = store__scalar(s, &o.seq, STORE_SQL_FIT_SEQ, &o, "tt", f->model, gk);
    if (rc == 0)
        rc = store__exec(s, STORE_SQL_FIT_DEL, &o, "");
    if (rc == 0)
        rc = store__exec(s, STORE_SQL_FIT_INS, &o, "ttttddddiitbbd", f->model,
            gk, f->formula, f->response, f->r2, f->rmse, f->mape, f->cv_mape,
            f->n_points, f->n_excluded, f->termination, f->measured, np,
            f->predicted, np, f->condition);
    free(gk);
    if (rc == 0)
        rc = store__fit_children(s, &o, f);
    return rc;
}

/* Inserts the run row, environment and warnings; DM_ERR_EXISTS if present. */
static int store__run_write(store *s, const dm_run_result *r, const char *tag)
{
    store__owner o = { r->id, NULL, 0 };
    long one;
    int rc = store__scalar(s, &one, STORE_SQL_RUN_EXISTS, &o, "");
    if (rc == 0)
        return store__failf(s, DM_ERR_EXISTS, "run '%s' already exists", r->id);
    if (rc != DM_ERR_NOTFOUND)
        return rc;
    rc = store__exec(s, STORE_SQL_RUN_INS, &o, "ttttdtt", r->sweep, r->started,
                     r->finished, r->sweep_hash, r->gpu_time_coverage,
                     r->timer_verdict, tag);
    if (rc == 0)
        rc = store__kv_write(s, STORE_SQL_ENV_INS, &o, r->environment,
                             r->n_environment);
    if (rc == 0)
        rc = store__strv_write(s, STORE_SQL_RWARN_INS, &o, r->warnings,
                               r->n_warnings);
    return rc;
}

/* ---- reading ------------------------------------------------------------------ */

static int store__kv_read(store *s, enum store_sql id, const store__owner *o,
                          dm_kv **kv, size_t *n)
{
    sqlite3_stmt *st = store__query(s, id, o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store__row(s, st)) == 1) {
        dm_kv *e = dm_vec_push(kv, n, NULL, sizeof *e);
        e->key = store__col_str(st, 0);
        e->value = store__col_str(st, 1);
    }
    return rc;
}

static int store__strv_read(store *s, enum store_sql id, const store__owner *o,
                            char ***v, size_t *n)
{
    sqlite3_stmt *st = store__query(s, id, o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store__row(s, st)) == 1)
        *(char **)dm_vec_push(v, n, NULL, sizeof **v) = store__col_str(st, 0);
    return rc;
}

/* Reads a query's first column as integers (the seq of left-out / fits). */
static void store__push_seq(sqlite3_stmt *st, long **seqs, size_t *n)
{
    *(long *)dm_vec_push(seqs, n, NULL, sizeof **seqs) = (long)sqlite3_column_int64(st, 0);
}

static void store__counter_cols(sqlite3_stmt *st, dm_counter_result *k)
{
    k->name = store__col_str(st, 0);
    k->unit = store__col_str(st, 1);
    k->available = sqlite3_column_int(st, 2);
    k->unavailable_reason = store__col_str(st, 3);
    k->deterministic = sqlite3_column_int(st, 4);
    k->partial = sqlite3_column_int(st, 5);
    k->value = store__col_double(st, 6);
    k->has_samples = sqlite3_column_int(st, 7);
    double *stats[] = { &k->median, &k->mean, &k->min, &k->max, &k->stddev,
                        &k->mad, &k->cv, &k->ci_lo, &k->ci_hi };
    for (int i = 0; i < 9; i++)
        *stats[i] = store__col_double(st, 8 + i);
    k->n_outliers = sqlite3_column_int(st, 17);
    k->n_nonfinite = sqlite3_column_int(st, 18);
}

static int store__samples_read(store *s, const store__owner *o, dm_counter_result *k)
{
    sqlite3_stmt *st = store__query(s, STORE_SQL_SMP_SEL, o, "t", k->name);
    int rc = st ? store__row(s, st) : DM_ERR_STORE;
    if (rc == 1) {
        k->samples = store__col_doubles(st, 0, &k->n_samples);
        sqlite3_reset(st);
        rc = 0;
    }
    return rc;
}

static int store__counters_read(store *s, const store__owner *o, dm_config_result *c)
{
    sqlite3_stmt *st = store__query(s, STORE_SQL_CTR_SEL, o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store__row(s, st)) == 1)
        store__counter_cols(st, dm_vec_push(&c->counters, &c->n_counters, NULL,
                                            sizeof *c->counters));
    for (size_t i = 0; i < c->n_counters && rc == 0; i++)
        if (c->counters[i].has_samples)
            rc = store__samples_read(s, o, &c->counters[i]);
    for (size_t i = 0; i < c->n_counters; i++)
        dm_counter_read_check(&c->counters[i], "the results store");
    return rc;
}

static void store__config_cols(sqlite3_stmt *st, dm_config_result *c)
{
    dm_quality *q = &c->quality;
    c->key = store__col_str(st, 0);
    c->scene = store__col_str(st, 1);
    c->ok = sqlite3_column_text(st, 2) &&
            strcmp((const char *)sqlite3_column_text(st, 2), "ok") == 0;
    c->reason = store__col_str(st, 3);
    c->log = store__col_str(st, 4);
    q->present = sqlite3_column_int(st, 5);
    double *m[] = { &q->rmse, &q->psnr, &q->ssim, &q->max_error,
                    &q->pct_over_threshold, &q->silhouette_error, &q->depth_rmse };
    for (int i = 0; i < 7; i++)
        *m[i] = store__col_double(st, 6 + i);
    q->crack_pixels = (long)sqlite3_column_int64(st, 13);
    q->nonfinite_pixels = (long)sqlite3_column_int64(st, 14);
    q->reference = store__col_str(st, 15);
    c->img_render = store__col_str(st, 16);
    c->img_heatmap = store__col_str(st, 17);
    c->img_reference = store__col_str(st, 18);
    double *f[] = { &q->flip, &q->flip_q1, &q->flip_median, &q->flip_q3, &q->flip_max, &q->flip_ppd };
    for (int i = 0; i < 6; i++)
        *f[i] = store__col_double(st, 19 + i);
    c->img_flip = store__col_str(st, 25);
}

static int store__configs_read(store *s, dm_run_result *r)
{
    store__owner o = { r->id, NULL, 0 };
    sqlite3_stmt *st = store__query(s, STORE_SQL_CFG_SEL, &o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store__row(s, st)) == 1)
        store__config_cols(st, dm_vec_push(&r->configs, &r->n_configs, NULL,
                                           sizeof *r->configs));
    for (size_t i = 0; i < r->n_configs && rc == 0; i++) {
        dm_config_result *c = &r->configs[i];
        o.key = c->key;
        rc = store__kv_read(s, STORE_SQL_CPAR_SEL, &o, &c->params, &c->n_params);
        if (rc == 0)
            rc = store__counters_read(s, &o, c);
    }
    return rc;
}

static int store__left_out_read(store *s, dm_run_result *r)
{
    store__owner o = { r->id, NULL, 0 };
    sqlite3_stmt *st = store__query(s, STORE_SQL_LO_SEL, &o, "");
    long *seqs = NULL;
    size_t n_seqs = 0;
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store__row(s, st)) == 1) {
        store__push_seq(st, &seqs, &n_seqs);
        dm_left_out *l = dm_vec_push(&r->left_out, &r->n_left_out, NULL, sizeof *l);
        l->reason = store__col_str(st, 1);
    }
    for (size_t i = 0; i < r->n_left_out && rc == 0; i++) {
        dm_left_out *l = &r->left_out[i];
        o.seq = seqs[i];
        rc = store__kv_read(s, STORE_SQL_LOPAR_SEL, &o, &l->params, &l->n_params);
    }
    free(seqs);
    return rc;
}

static int store__fit_params_read(store *s, const store__owner *o, dm_fit_result *f)
{
    sqlite3_stmt *st = store__query(s, STORE_SQL_FPAR_SEL, o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store__row(s, st)) == 1) {
        dm_fit_param *p = dm_vec_push(&f->params, &f->n_params, NULL, sizeof *p);
        p->name = store__col_str(st, 0);
        p->value = store__col_double(st, 1);
        p->stderr_ = store__col_double(st, 2);
    }
    return rc;
}

static int store__fit_labels_read(store *s, const store__owner *o, dm_fit_result *f)
{
    sqlite3_stmt *st = store__query(s, STORE_SQL_FLBL_SEL, o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store__row(s, st)) == 1) {
        long i = (long)sqlite3_column_int64(st, 0);
        if (!f->point_labels)
            f->point_labels = dm_xcalloc((size_t)f->n_points + 1, sizeof(char *));
        if (i >= 0 && i < f->n_points && !f->point_labels[i])
            f->point_labels[i] = store__col_str(st, 1);
    }
    return rc;
}

/* Fills the columns of one fit row; DM_ERR_STORE when its point arrays do
 * not hold n_points values. */
static int store__fit_cols(store *s, sqlite3_stmt *st, dm_fit_result *f)
{
    size_t nm = 0, np = 0;
    f->model = store__col_str(st, 1);
    f->formula = store__col_str(st, 2);
    f->response = store__col_str(st, 3);
    f->r2 = store__col_double(st, 4);
    f->rmse = store__col_double(st, 5);
    f->mape = store__col_double(st, 6);
    f->cv_mape = store__col_double(st, 7);
    f->n_points = sqlite3_column_int(st, 8);
    f->n_excluded = sqlite3_column_int(st, 9);
    f->termination = store__col_str(st, 10);
    f->measured = store__col_doubles(st, 11, &nm);
    f->predicted = store__col_doubles(st, 12, &np);
    f->condition = store__col_double(st, 13);
    if (f->n_points < 0 || (f->measured && nm != (size_t)f->n_points) ||
        (f->predicted && np != (size_t)f->n_points)) {
        f->n_points = 0;
        return store__failf(s, DM_ERR_STORE, "fit '%s': point arrays do not "
                            "hold n_points values", f->model);
    }
    return 0;
}

static int store__fit_children_read(store *s, const store__owner *o,
                                    dm_fit_result *f)
{
    int rc = store__kv_read(s, STORE_SQL_FGRP_SEL, o, &f->group, &f->n_group);
    if (rc == 0)
        rc = store__fit_params_read(s, o, f);
    if (rc == 0)
        rc = store__strv_read(s, STORE_SQL_FWARN_SEL, o, &f->warnings,
                              &f->n_warnings);
    if (rc == 0)
        rc = store__fit_labels_read(s, o, f);
    return rc;
}

static int store__fits_read(store *s, dm_run_result *r)
{
    store__owner o = { r->id, NULL, 0 };
    sqlite3_stmt *st = store__query(s, STORE_SQL_FIT_SEL, &o, "");
    long *seqs = NULL;
    size_t n_seqs = 0;
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store__row(s, st)) == 1) {
        store__push_seq(st, &seqs, &n_seqs);
        if (store__fit_cols(s, st, dm_vec_push(&r->fits, &r->n_fits, NULL,
                                               sizeof *r->fits)) < 0) {
            sqlite3_reset(st);
            rc = DM_ERR_STORE;
        }
    }
    for (size_t i = 0; i < r->n_fits && rc == 0; i++) {
        o.seq = seqs[i];
        rc = store__fit_children_read(s, &o, &r->fits[i]);
    }
    free(seqs);
    return rc;
}

static int store__run_row(store *s, dm_run_result *r)
{
    store__owner o = { r->id, NULL, 0 };
    sqlite3_stmt *st = store__query(s, STORE_SQL_RUN_SEL, &o, "");
    int rc = st ? store__row(s, st) : DM_ERR_STORE;
    if (rc == 0)
        return store__failf(s, DM_ERR_NOTFOUND, "run '%s' is not in the store",
                            r->id);
    if (rc < 0)
        return rc;
    r->sweep = store__col_str(st, 0);
    r->started = store__col_str(st, 1);
    r->finished = store__col_str(st, 2);
    r->sweep_hash = store__col_str(st, 3);
    r->gpu_time_coverage = store__col_double(st, 4);
    r->timer_verdict = store__col_str(st, 5);
    sqlite3_reset(st);
    return 0;
}

/* Reads everything of run r->id into r = c->out (in a read transaction). */
static int store__run_read(store *s, const store__call *c)
{
    dm_run_result *r = c->out;
    store__owner o = { r->id, NULL, 0 };
    int rc = store__run_row(s, r);
    if (rc == 0)
        rc = store__kv_read(s, STORE_SQL_ENV_SEL, &o, &r->environment,
                            &r->n_environment);
    if (rc == 0)
        rc = store__strv_read(s, STORE_SQL_RWARN_SEL, &o, &r->warnings,
                              &r->n_warnings);
    if (rc == 0)
        rc = store__configs_read(s, r);
    if (rc == 0)
        rc = store__left_out_read(s, r);
    if (rc == 0)
        rc = store__fits_read(s, r);
    return rc;
}

/* ---- opening ------------------------------------------------------------------ */

/* Brings the schema to STORE_SCHEMA_VERSION inside one write transaction
 * (re-reading the version there, so two processes opening a new file at
 * once do not both create it); a newer schema is refused. */
static int store__migrate(store *s)
{
    long v = 0;
    sqlite3_stmt *st = NULL;
    int rc = sqlite3_exec(s->db, "BEGIN IMMEDIATE", NULL, NULL, NULL);
    if (rc == SQLITE_OK)
        rc = sqlite3_prepare_v2(s->db, "PRAGMA user_version", -1, &st, NULL);
    if (rc == SQLITE_OK && sqlite3_step(st) == SQLITE_ROW)
        v = (long)sqlite3_column_int64(st, 0);
    rc = rc == SQLITE_OK ? sqlite3_finalize(st) : rc;
    if (rc == SQLITE_OK && v > STORE_SCHEMA_VERSION) {
        sqlite3_exec(s->db, "ROLLBACK", NULL, NULL, NULL);
        return store__failf(s, DM_ERR_STORE, "the results store was written by a newer dmbench "
                            "(schema version %ld; this one reads up to %d): open it with that "
                            "dmbench, or give another --out", v, STORE_SCHEMA_VERSION);
    }
    int upgrade = v < STORE_SCHEMA_VERSION;
    for (; rc == SQLITE_OK && v < STORE_SCHEMA_VERSION; v++)
        rc = sqlite3_exec(s->db, store__migrations[v], NULL, NULL, NULL);
    if (rc == SQLITE_OK && upgrade)
        rc = sqlite3_exec(s->db, "PRAGMA user_version=" STORE__STR(STORE_SCHEMA_VERSION),
                          NULL, NULL, NULL);
    if (rc == SQLITE_OK)
        rc = sqlite3_exec(s->db, "COMMIT", NULL, NULL, NULL);
    if (rc == SQLITE_OK)
        return 0;
    rc = store__fail(s, "creating the schema");
    if (!sqlite3_get_autocommit(s->db))
        sqlite3_exec(s->db, "ROLLBACK", NULL, NULL, NULL);
    return rc;
}

/* A reference schema: every migration applied to an empty in-memory
 * database, so the expected tables and columns come from the one place that
 * creates them.  Returns the connection (caller closes) or NULL. */
static sqlite3 *store__reference_schema(void)
{
    sqlite3 *ref = NULL;
    int rc = sqlite3_open_v2(":memory:", &ref, SQLITE_OPEN_READWRITE, NULL);
    for (int v = 0; rc == SQLITE_OK && v < STORE_SCHEMA_VERSION; v++)
        rc = sqlite3_exec(ref, store__migrations[v], NULL, NULL, NULL);
    if (rc != SQLITE_OK) {
        sqlite3_close(ref);
        return NULL;
    }
    return ref;
}

/* Every (table, column) of db as "\ttable\tcolumn\n" lines into out. */
static int store__columns(sqlite3 *db, dm_str *out)
{
    sqlite3_stmt *st = NULL;
    int rc = sqlite3_prepare_v2(db, "SELECT m.name, p.name FROM sqlite_schema m, "
                                "pragma_table_info(m.name) p WHERE m.type = 'table' "
                                "ORDER BY m.rowid, p.cid", -1, &st, NULL);
    while (rc == SQLITE_OK && (rc = sqlite3_step(st)) == SQLITE_ROW) {
        dm_str_printf(out, "\t%s\t%s\n", (const char *)sqlite3_column_text(st, 0),
                      (const char *)sqlite3_column_text(st, 1));
        rc = SQLITE_OK;
    }
    sqlite3_finalize(st);
    return rc == SQLITE_DONE ? SQLITE_OK : rc;
}

/* Checks that every table and column of the reference schema is in the
 * file.  A table dropped or a column lost (a hand edit, a partial restore,
 * another program) makes the store damaged now, at open, instead of a
 * "run not found" or a half-read run later.  0, or DM_ERR_STORE naming the
 * first table or column missing. */
static int store__verify_schema(store *s)
{
    sqlite3 *ref = store__reference_schema();
    dm_str want = {0}, have = {0};
    int rc = ref ? store__columns(ref, &want) : SQLITE_NOMEM;
    rc = rc == SQLITE_OK ? store__columns(s->db, &have) : rc;
    sqlite3_close(ref);
    int missing = 0;
    for (char *line = want.buf; rc == SQLITE_OK && !missing && line && *line;) {
        char *table = line + 1, *tab = strchr(table, '\t'), *end = strchr(tab, '\n');
        *tab = *end = '\0';
        char *col = tab + 1, *pair = dm_xasprintf("\t%s\t%s\n", table, col);
        char *prefix = dm_xasprintf("\t%s\t", table);
        if (!strstr(dm_str_get(&have), pair))
            missing = strstr(dm_str_get(&have), prefix)
                ? store__failf(s, DM_ERR_STORE, "the results store is damaged: column '%s' of "
                               "table '%s' is missing; restore dmbench.sqlite from a backup, or "
                               "give another --out", col, table)
                : store__failf(s, DM_ERR_STORE, "the results store is damaged: table '%s' is "
                               "missing; restore dmbench.sqlite from a backup, or give another "
                               "--out", table);
        free(pair);
        free(prefix);
        line = end + 1;
    }
    dm_str_free(&want);
    dm_str_free(&have);
    if (missing)
        return missing;
    return rc == SQLITE_OK ? 0 : store__fail(s, "checking the schema");
}

/* Opening failures caused by the path are I/O errors (the user's); a disk
 * that refuses the write (full, ulimit -f: dm_disk_errno) is DM_ERR_DISK; the
 * rest (not a database, corrupt, out of memory) are store errors. */
static int store__open_code(store *s, int rc)
{
    int prim = rc & 0xff;
    if (prim == SQLITE_FULL || (prim == SQLITE_IOERR && s->db && dm_disk_errno(sqlite3_system_errno(s->db))))
        return DM_ERR_DISK;
    return prim == SQLITE_CANTOPEN || prim == SQLITE_READONLY ||
           prim == SQLITE_PERM || prim == SQLITE_IOERR ? DM_ERR_IO : DM_ERR_STORE;
}

static int store__connect(store *s)
{
    int rc = sqlite3_open_v2(s->path, &s->db,
                             SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, NULL);
    if (rc == SQLITE_OK)
        rc = sqlite3_busy_timeout(s->db, 5000);
    if (rc == SQLITE_OK)
        rc = sqlite3_exec(s->db, "PRAGMA foreign_keys=ON;"
                          "PRAGMA journal_mode=WAL;PRAGMA synchronous=FULL",
                          NULL, NULL, NULL);
    if (rc != SQLITE_OK) {
        int code = store__open_code(s, s->db ? sqlite3_extended_errcode(s->db) : rc);
        store__fail(s, "cannot open the results store");
        return code;
    }
    rc = store__migrate(s);
    return rc ? rc : store__verify_schema(s);
}

int store_path_fits(const char *path, dm_str *err)
{
    sqlite3_vfs *vfs = sqlite3_vfs_find(NULL);
    char cwd[PATH_MAX] = "";
    size_t len = strlen(path);
    if (path[0] != '/')
        len += (getcwd(cwd, sizeof cwd) ? strlen(cwd) : 0) + 1;
    /* its rollback journal ("-journal") must fit the limit too */
    if (!vfs || len + 8 <= (size_t)vfs->mxPathname)
        return 0;
    dm_str_printf(err, "%s: the results store's path would be %zu bytes long; SQLite opens at most "
                  "%d: give a shorter --out", path, len, vfs->mxPathname - 8);
    return DM_ERR_ARG;
}

int store_open(const char *path, store **out, dm_str *err)
{
    *out = NULL;
    if (!path) {
        if (err)
            dm_str_cat(err, "results store: no path given");
        return DM_ERR_ARG;
    }
    store *s = dm_xcalloc(1, sizeof *s);
    s->path = dm_xstrdup(path);
    int rc = store__connect(s);
    if (rc < 0) {
        if (err)
            dm_str_cat(err, store_last_error(s));
        store_close(s);
        return rc;
    }
    *out = s;
    return 0;
}

int store_check(store *s, dm_str *err)
{
    sqlite3_stmt *st = NULL;
    int rc = sqlite3_prepare_v2(s->db, "PRAGMA quick_check(1)", -1, &st, NULL);
    int step = rc == SQLITE_OK ? sqlite3_step(st) : rc;
    const char *res = step == SQLITE_ROW ? (const char *)sqlite3_column_text(st, 0) : NULL;
    int ok = res && strcmp(res, "ok") == 0;
    if (!ok) {
        char *why = dm_xstrdup(res ? res : sqlite3_errmsg(s->db));
        for (char *p = why; *p; p++)
            *p = *p == '\n' ? ' ' : *p;
        store__failf(s, DM_ERR_STORE, "the results store is damaged (%s); restore it from a "
                     "backup or give another --out", why);
        free(why);
    }
    sqlite3_finalize(st);
    if (!ok && err)
        dm_str_cat(err, store_last_error(s));
    return ok ? 0 : DM_ERR_STORE;
}

void store_close(store *s)
{
    if (!s)
        return;
    for (int i = 0; i < STORE_SQL_COUNT; i++)
        sqlite3_finalize(s->st[i]);
    sqlite3_close(s->db);
    free(s->path);
    dm_str_free(&s->err);
    free(s);
}

/* ---- public operations ---------------------------------------------------------- */

static int store__begin_fn(store *s, const store__call *c)
{
    return store__run_write(s, c->item, c->text);
}

int store_run_begin(store *s, const dm_run_result *run, const char *tag)
{
    if (!run || !run->id)
        return store__failf(s, DM_ERR_ARG, "run without an id");
    store__call c = { .item = run, .text = tag };
    return store__tx(s, 1, store__begin_fn, &c);
}

static int store__put_fn(store *s, const store__call *c)
{
    int rc = store__need_run(s, c->run);
    return rc ? rc : c->write(s, c->run, c->item);
}

/* Writes item into run run_id with write, in one write transaction;
 * DM_ERR_NOTFOUND (and nothing written) when the run is not in the store. */
static int store__put(store *s, const char *run_id, const void *item, store__writer write)
{
    store__call c = { .run = run_id, .item = item, .write = write };
    return store__tx(s, 1, store__put_fn, &c);
}

static int store__warning_write(store *s, const char *run, const void *text)
{
    store__owner o = { run, NULL, 0 };
    return store__exec(s, STORE_SQL_RWARN_INS, &o, "t", (const char *)text);
}

int store_run_warning_put(store *s, const char *run_id, const char *text)
{
    return store__put(s, run_id, text, store__warning_write);
}

static int store__env_write(store *s, const char *run, const void *kv)
{
    store__owner o = { run, NULL, 0 };
    return store__kv_write(s, STORE_SQL_ENV_INS, &o, kv, 1);
}

int store_run_env_put(store *s, const char *run_id, const char *key, const char *value)
{
    dm_kv kv = { (char *)key, (char *)value };
    return store__put(s, run_id, &kv, store__env_write);
}

int store_config_put(store *s, const char *run_id, const dm_config_result *cfg)
{
    return store__put(s, run_id, cfg, store__config_write);
}

static int store__partial_fn(store *s, const store__call *c)
{
    const store_partial *items = c->item;
    size_t n = *(const size_t *)c->out;
    int rc = store__need_run(s, c->run);
    for (size_t i = 0; rc == 0 && i < n; i++) {
        store__owner o = { c->run, items[i].key, 0 };
        rc = store__exec(s, STORE_SQL_PART_DEL, &o, "");
        for (size_t k = 0; rc == 0 && k < items[i].n_counters; k++)
            rc = store__exec(s, STORE_SQL_PART_INS, &o, "tbl", items[i].counters[k],
                             items[i].samples[k], items[i].n_samples, items[i].sampling_ns);
    }
    return rc;
}

int store_partial_put(store *s, const char *run_id, const store_partial *items, size_t n)
{
    store__call c = { .run = run_id, .item = items, .out = &n };
    return store__tx(s, 1, store__partial_fn, &c);
}

int store_partial_get(store *s, const char *run_id, const char *key, const char *counter,
                      double **v, size_t *n, long *sampling_ns)
{
    store__owner o = { run_id, key, 0 };
    *v = NULL;
    *n = 0;
    sqlite3_stmt *st = store__query(s, STORE_SQL_PART_SEL, &o, "t", counter);
    int rc = st ? store__row(s, st) : DM_ERR_STORE;
    if (rc != 1)
        return rc < 0 ? rc : DM_ERR_NOTFOUND;
    *v = store__col_doubles(st, 0, n);
    *sampling_ns = (long)sqlite3_column_int64(st, 1);
    sqlite3_reset(st);
    return 0;
}

int store_left_out_put(store *s, const char *run_id, const dm_left_out *l)
{
    return store__put(s, run_id, l, store__left_out_write);
}

int store_fit_put(store *s, const char *run_id, const dm_fit_result *f)
{
    return store__put(s, run_id, f, store__fit_write);
}

static int store__finish_write(store *s, const char *run, const void *iso)
{
    store__owner o = { run, NULL, 0 };
    return store__exec(s, STORE_SQL_RUN_FINISH, &o, "t", (const char *)iso);
}

int store_run_finish(store *s, const char *run_id, const char *finished_iso)
{
    return store__put(s, run_id, finished_iso, store__finish_write);
}

int store_config_done(store *s, const char *run_id, const char *key)
{
    long one;
    store__owner o = { run_id, key, 0 };
    int rc = store__scalar(s, &one, STORE_SQL_CFG_DONE, &o, "");
    return rc == 0 ? 1 : rc == DM_ERR_NOTFOUND ? 0 : rc;
}

int store_run_load(store *s, const char *run_id, dm_run_result *out)
{
    memset(out, 0, sizeof *out);
    out->id = dm_xstrdup(run_id);
    store__call c = { .run = run_id, .out = out };
    int rc = store__tx(s, 0, store__run_read, &c);
    if (rc < 0)
        dm_run_free(out);
    return rc;
}

int store_run_tag(store *s, const char *run_id, char **tag)
{
    store__owner o = { run_id, NULL, 0 };
    *tag = NULL;
    sqlite3_stmt *st = store__query(s, STORE_SQL_RUN_TAG, &o, "");
    int rc = st ? store__row(s, st) : DM_ERR_STORE;
    if (rc == 0)
        return store__failf(s, DM_ERR_NOTFOUND, "run '%s' is not in the store",
                            run_id);
    if (rc == 1) {
        *tag = store__col_str(st, 0);
        sqlite3_reset(st);
        rc = 0;
    }
    return rc;
}

/* Run ids newest first, only those tagged tag unless it is NULL, at most
 * max of them; on failure *ids is NULL and *n 0. */
static int store__runs(store *s, const char *tag, size_t max, char ***ids, size_t *n)
{
    *ids = NULL;
    *n = 0;
    sqlite3_stmt *st = store__query(s, STORE_SQL_RUN_LIST, NULL, "t", tag);
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && *n < max && (rc = store__row(s, st)) == 1)
        *(char **)dm_vec_push(ids, n, NULL, sizeof **ids) = store__col_str(st, 0);
    if (rc == 1)
        sqlite3_reset(st);
    if (rc >= 0)
        return 0;
    for (size_t i = 0; i < *n; i++)
        free((*ids)[i]);
    free(*ids);
    *ids = NULL;
    *n = 0;
    return rc;
}

int store_latest_run(store *s, const char *tag, char **id)
{
    char **ids;
    size_t n;
    *id = NULL;
    int rc = store__runs(s, tag, 1, &ids, &n);
    if (rc == 0 && n == 0)
        return store__failf(s, DM_ERR_NOTFOUND, "no run%s%s in the store",
                            tag ? " tagged " : "", tag ? tag : "");
    if (rc == 0)
        *id = ids[0];
    free(ids);
    return rc;
}

int store_list_runs(store *s, char ***ids, size_t *n)
{
    return store__runs(s, NULL, (size_t)-1, ids, n);
}

/* Writes every part of the loaded run c->item, tagged c->text. */
static int store__copy_fn(store *s, const store__call *c)
{
    const dm_run_result *r = c->item;
    int rc = store__run_write(s, r, c->text);
    for (size_t i = 0; i < r->n_configs && rc == 0; i++)
        rc = store__config_write(s, r->id, &r->configs[i]);
    for (size_t i = 0; i < r->n_left_out && rc == 0; i++)
        rc = store__left_out_write(s, r->id, &r->left_out[i]);
    for (size_t i = 0; i < r->n_fits && rc == 0; i++)
        rc = store__fit_write(s, r->id, &r->fits[i]);
    return rc;
}

int store_copy_run(store *dst, store *src, const char *run_id)
{
    dm_run_result r;
    char *tag = NULL;
    int rc = store_run_load(src, run_id, &r);
    if (rc == 0)
        rc = store_run_tag(src, run_id, &tag);
    if (rc < 0) {
        store__failf(dst, rc, "copying run '%s': %s", run_id, store_last_error(src));
    } else {
        store__call c = { .run = run_id, .item = &r, .text = tag };
        rc = store__tx(dst, 1, store__copy_fn, &c);
    }
    free(tag);
    dm_run_free(&r);
    return rc;
}
