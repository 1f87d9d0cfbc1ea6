/* store_sql.h — the results store's SQL: the schema's version and migration
 * (store_schema.c), the statements store.c runs, and the layer that runs
 * them (store_sql.c).  store/'s own header: only store.c, store_sql.c and
 * store_schema.c include it.
 *
 * Statements are listed once, in STORE_SQL(X); each child statement takes
 * its owner as ?1 run, ?2 configuration key, ?3 seq (each uses the ones it
 * needs) and its payload from ?4.  The tables they name are described at the
 * top of store_schema.c.
 */
#ifndef STORE_STORE_SQL_H
#define STORE_STORE_SQL_H

#include "store/store.h"
#include "core/dm_util.h"

#include <sqlite3.h>

#include <stddef.h>

#define STORE_SCHEMA_VERSION 8

#define STORE__CFG_COLS "scene,status,reason,log,q_present,q_rmse,q_psnr," \
    "q_ssim,q_max_error,q_pct_over,q_silhouette,q_depth_rmse,q_crack_pixels," \
    "q_nonfinite_pixels,q_reference,img_render,img_heatmap,img_reference," \
    "q_flip,q_flip_q1,q_flip_median,q_flip_q3,q_flip_max,q_flip_ppd,img_flip"
#define STORE__CTR_COLS "unit,available,unavailable_reason,deterministic," \
    "partial,value,has_samples,median,mean,min,max,stddev,mad,cv,ci_lo," \
    "ci_hi,n_outliers,n_nonfinite,corrected,corr_median,corr_ci_lo,corr_ci_hi"
#define STORE__PQ_COLS "computed,reason,frames,every,temporal_mean,temporal_p99," \
    "popping,popping_frame,img_temporal,flip,ssim"
#define STORE__PREC_COLS "corrected,reason,predictor,n_rounds,machine_spread," \
    "raw_noise,loo_noise,calib_noise,resolvable"
#define STORE__PATH_COLS "frames,replays,data,p50,p95,p99,low1_ns,low1_fps," \
    "stutter_at,replay_spread,noisy"
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
      "?21,?22,?23,?24,?25,?26)")                                             \
    X(CTR_CORR, "UPDATE counters SET corrected=?5,corr_median=?6,"            \
      "corr_ci_lo=?7,corr_ci_hi=?8 WHERE run=?1 AND key=?2 AND name=?4")      \
    X(ROUND_INS, "INSERT INTO rounds(run,scene,seq,keys,calib_ns) VALUES(?1," \
      "?4,(SELECT IFNULL(MAX(seq),-1)+1 FROM rounds WHERE run=?1 AND"         \
      " scene=?4),?5,?6)")                                                    \
    X(ROUND_SEL, "SELECT scene,seq,keys,calib_ns FROM rounds WHERE run=?1"    \
      " ORDER BY scene,seq")                                                  \
    X(PREC_INS, "INSERT OR REPLACE INTO scene_precision(run,scene,"           \
      STORE__PREC_COLS ") VALUES(?1,?4,?5,?6,?7,?8,?9,?10,?11,?12,?13)")      \
    X(PREC_SEL, "SELECT scene," STORE__PREC_COLS " FROM scene_precision"      \
      " WHERE run=?1 ORDER BY rowid")                                         \
    X(PQ_INS, "INSERT INTO path_quality(run,key," STORE__PQ_COLS ") VALUES"   \
      "(?1,?2,?4,?5,?6,?7,?8,?9,?10,?11,?12,?13,?14)")                        \
    X(PQ_SEL, "SELECT " STORE__PQ_COLS " FROM path_quality WHERE run=?1 AND"  \
      " key=?2")                                                              \
    X(SHOT_INS, "INSERT INTO path_shots(run,key,seq,frame,img_test,img_ref,"  \
      "img_flip) VALUES(?1,?2,?3,?4,?5,?6,?7)")                               \
    X(SHOT_SEL, "SELECT frame,img_test,img_ref,img_flip FROM path_shots"      \
      " WHERE run=?1 AND key=?2 ORDER BY seq")                                \
    X(CTR_SEL, "SELECT name," STORE__CTR_COLS " FROM counters WHERE run=?1"   \
      " AND key=?2 ORDER BY rowid")                                           \
    X(SMP_INS, "INSERT INTO samples(run,key,counter,data) VALUES(?1,?2,?4,?5)")\
    X(SMP_SEL, "SELECT data FROM samples WHERE run=?1 AND key=?2 AND"         \
      " counter=?4")                                                          \
    X(PATH_INS, "INSERT INTO path_frames(run,key," STORE__PATH_COLS ")"       \
      " VALUES(?1,?2,?4,?5,?6,?7,?8,?9,?10,?11,?12,?13,?14)")                 \
    X(PATH_SEL, "SELECT " STORE__PATH_COLS " FROM path_frames WHERE run=?1"   \
      " AND key=?2")                                                          \
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

/* ---- statements (store_sql.c) ---------------------------------------------- */

struct store {
    sqlite3 *db;
    char *path;
    dm_str err;
    sqlite3_stmt *st[STORE_SQL_COUNT];
};

/* Who a child row belongs to: bound as ?1, ?2, ?3 of every statement. */
typedef struct store_sql_owner {
    const char *run;
    const char *key;
    long seq;
} store_sql_owner;

/* Replaces the last error with "path: <formatted>" and returns code. */
int store_sql_failf(store *s, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* Records SQLite's current message for what was being done; DM_ERR_STORE. */
int store_sql_fail(store *s, const char *what);

/* The cached statement id, reset, with owner o (NULL: none) in ?1..?3 and
 * the payload from ?4, one kind letter of fmt per parameter: t text (NULL
 * ok), i int, l long, d double (NaN stored as NULL), b doubles (const double
 * *, size_t n) as a blob, NULL pointer → NULL.  NULL with the error recorded
 * on failure; a payload that does not match the statement's parameters is
 * refused (DM_ERR_MISUSE). */
sqlite3_stmt *store_sql_query(store *s, enum store_sql id, const store_sql_owner *o,
                              const char *fmt, ...);
/* Steps a prepared query: 1 with a row, 0 at the end (statement reset),
 * DM_ERR_STORE on failure (statement reset). */
int store_sql_row(store *s, sqlite3_stmt *st);
/* Runs a statement for its effect (a row it may return is ignored). */
int store_sql_exec(store *s, enum store_sql id, const store_sql_owner *o, const char *fmt, ...);
/* Runs a one-integer query into *v; DM_ERR_NOTFOUND when it returns no row. */
int store_sql_scalar(store *s, long *v, enum store_sql id, const store_sql_owner *o,
                     const char *fmt, ...);

/* Column i as a malloc'd array of doubles (NULL for a NULL column). */
double *store_sql_col_doubles(sqlite3_stmt *st, int i, size_t *n);
/* Column i as a double, NULL read as NaN. */
double store_sql_col_double(sqlite3_stmt *st, int i);
/* Column i as a malloc'd string. */
char *store_sql_col_str(sqlite3_stmt *st, int i);

/* ---- schema (store_schema.c) ------------------------------------------------ */

/* store_schema_migrate's answer when the file's schema is newer than
 * STORE_SCHEMA_VERSION (SQLite's codes are never negative). */
#define STORE_SCHEMA_NEWER (-1)

/* Brings db's schema to STORE_SCHEMA_VERSION inside one write transaction
 * (re-reading the version there, so two processes opening a new file at
 * once do not both create it).  SQLITE_OK; STORE_SCHEMA_NEWER with the
 * file's version in *found (the transaction rolled back); or the failing
 * SQLite code, db's error message still set and the transaction possibly
 * open, for the caller to report and roll back. */
int store_schema_migrate(sqlite3 *db, long *found);
/* The first table or column of the schema that db lacks, compared with
 * every migration applied to an empty in-memory database, so the expected
 * tables and columns come from the one place that creates them.  SQLITE_OK
 * with *table NULL (nothing missing), *table set and *column NULL (the table
 * is missing), or both set (the column is); both malloc'd.  Else an SQLite
 * code, db's message set. */
int store_schema_missing(sqlite3 *db, char **table, char **column);

#endif
