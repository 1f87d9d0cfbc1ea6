/* store_schema.c — the results store's schema: the migrations that create
 * it and the check that a file has all of it (store_sql.h).
 *
 * Schema (version 8, kept in PRAGMA user_version; store_schema__migrations[i] takes a
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
 *            max, stddev, mad, cv, ci_lo, ci_hi, n_outliers, n_nonfinite,
 *            corrected, corr_median, corr_ci_lo, corr_ci_hi (version 5: 0
 *            and NULL for older runs))
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
 *   rounds(run, scene, seq, keys, calib_ns) PK (run, scene, seq): each
 *           round of a scene's timing samples, its configurations in the
 *           order sampled and the calibration kernel's time (version 5)
 *   scene_precision(run, scene, corrected, reason, predictor, n_rounds,
 *           machine_spread, raw_noise, loo_noise, calib_noise, resolvable)
 *           PK (run, scene): the drift removed per scene (version 5)
 *   path_frames(run, key, frames, replays, data BLOB, p50, p95, p99,
 *           low1_ns, low1_fps, stutter_at BLOB, replay_spread, noisy)
 *           PK (run, key) → configs: the frame times of a configuration on
 *           a camera path, replays × frames doubles (ns, row = replay), and
 *           their summary (dm_path_series; the stutters' frame indices as
 *           doubles; version 6)
 *   path_quality(run, key, computed, reason, frames, every, temporal_mean,
 *           temporal_p99, popping, popping_frame, img_temporal, flip BLOB,
 *           ssim BLOB) PK (run, key) → configs: quality along a camera path
 *           (dm_path_quality; a row only where it was asked; version 7)
 *   path_shots(run, key, seq, frame, img_test, img_ref, img_flip) PK (run,
 *           key, seq) → configs: the frames of a path written as images
 *           for the report's filmstrip, in path order (dm_path_shot;
 *           version 8: older runs have none)
 *   fit_group(run, seq, key, value), fit_params(run, seq, name, value,
 *        stderr), fit_warnings(run, seq, text), fit_labels(run, seq, idx,
 *        label)
 *
 */
#include "store/store_sql.h"
#include "core/dm_util.h"

#include <stdlib.h>
#include <string.h>

#define STORE_SCHEMA__XSTR(x) #x
#define STORE_SCHEMA__STR(x) STORE_SCHEMA__XSTR(x)

static const char *const store_schema__migrations[STORE_SCHEMA_VERSION] = {
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
    /* 4 -> 5: figures with the machine's drift removed (models/drift.h),
     * the rounds' order and calibration, each scene's precision; a counter
     * of an older run is not corrected (0) */
    "ALTER TABLE counters ADD COLUMN corrected INTEGER DEFAULT 0;"
    "ALTER TABLE counters ADD COLUMN corr_median REAL;"
    "ALTER TABLE counters ADD COLUMN corr_ci_lo REAL;"
    "ALTER TABLE counters ADD COLUMN corr_ci_hi REAL;"
    "CREATE TABLE rounds(run TEXT NOT NULL REFERENCES runs(id) ON DELETE"
    " CASCADE, scene TEXT NOT NULL, seq INTEGER NOT NULL, keys TEXT,"
    " calib_ns REAL, PRIMARY KEY(run, scene, seq));"
    "CREATE TABLE scene_precision(run TEXT NOT NULL REFERENCES runs(id) ON"
    " DELETE CASCADE, scene TEXT NOT NULL, corrected INTEGER, reason TEXT,"
    " predictor TEXT, n_rounds INTEGER, machine_spread REAL, raw_noise REAL,"
    " loo_noise REAL, calib_noise REAL, resolvable REAL,"
    " PRIMARY KEY(run, scene));",
    /* 5 -> 6: the frame times of configurations on a camera path
     * (run/path_timing.h); a still configuration has no row */
    "CREATE TABLE path_frames(run TEXT NOT NULL, key TEXT NOT NULL,"
    " frames INTEGER NOT NULL, replays INTEGER NOT NULL, data BLOB,"
    " p50 REAL, p95 REAL, p99 REAL, low1_ns REAL, low1_fps REAL,"
    " stutter_at BLOB, replay_spread REAL, noisy INTEGER,"
    " PRIMARY KEY(run, key), FOREIGN KEY(run, key) REFERENCES configs(run, key)"
    " ON DELETE CASCADE);",
    /* 6 -> 7: quality along a camera path (run/mpath_quality.h): a row per
     * configuration that asked for it; older runs have none */
    "CREATE TABLE path_quality(run TEXT NOT NULL, key TEXT NOT NULL,"
    " computed INTEGER, reason TEXT, frames INTEGER, every INTEGER,"
    " temporal_mean REAL, temporal_p99 REAL, popping REAL, popping_frame"
    " INTEGER, img_temporal TEXT, flip BLOB, ssim BLOB, PRIMARY KEY(run, key),"
    " FOREIGN KEY(run, key) REFERENCES configs(run, key) ON DELETE CASCADE);",
    /* 7 -> 8: the frames of a path written as images (the report's
     * filmstrip); older runs have none and say so */
    "CREATE TABLE path_shots(run TEXT NOT NULL, key TEXT NOT NULL,"
    " seq INTEGER NOT NULL, frame INTEGER, img_test TEXT, img_ref TEXT,"
    " img_flip TEXT, PRIMARY KEY(run, key, seq), FOREIGN KEY(run, key)"
    " REFERENCES configs(run, key) ON DELETE CASCADE);",
};

int store_schema_migrate(sqlite3 *db, long *found)
{
    long v = 0;
    sqlite3_stmt *st = NULL;
    int rc = sqlite3_exec(db, "BEGIN IMMEDIATE", NULL, NULL, NULL);
    if (rc == SQLITE_OK)
        rc = sqlite3_prepare_v2(db, "PRAGMA user_version", -1, &st, NULL);
    if (rc == SQLITE_OK && sqlite3_step(st) == SQLITE_ROW)
        v = (long)sqlite3_column_int64(st, 0);
    rc = rc == SQLITE_OK ? sqlite3_finalize(st) : rc;
    if (rc == SQLITE_OK && v > STORE_SCHEMA_VERSION) {
        sqlite3_exec(db, "ROLLBACK", NULL, NULL, NULL);
        *found = v;
        return STORE_SCHEMA_NEWER;
    }
    int upgrade = v < STORE_SCHEMA_VERSION;
    for (; rc == SQLITE_OK && v < STORE_SCHEMA_VERSION; v++)
        rc = sqlite3_exec(db, store_schema__migrations[v], NULL, NULL, NULL);
    if (rc == SQLITE_OK && upgrade)
        rc = sqlite3_exec(db, "PRAGMA user_version=" STORE_SCHEMA__STR(STORE_SCHEMA_VERSION),
                          NULL, NULL, NULL);
    if (rc == SQLITE_OK)
        rc = sqlite3_exec(db, "COMMIT", NULL, NULL, NULL);
    return rc;
}

/* Every migration applied to an empty in-memory database.  Returns the
 * connection (caller closes) or NULL. */
static sqlite3 *store_schema__reference(void)
{
    sqlite3 *ref = NULL;
    int rc = sqlite3_open_v2(":memory:", &ref, SQLITE_OPEN_READWRITE, NULL);
    for (int v = 0; rc == SQLITE_OK && v < STORE_SCHEMA_VERSION; v++)
        rc = sqlite3_exec(ref, store_schema__migrations[v], NULL, NULL, NULL);
    if (rc != SQLITE_OK) {
        sqlite3_close(ref);
        return NULL;
    }
    return ref;
}

/* Every (table, column) of db as "\ttable\tcolumn\n" lines into out. */
static int store_schema__columns(sqlite3 *db, dm_str *out)
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

int store_schema_missing(sqlite3 *db, char **table, char **column)
{
    *table = *column = NULL;
    sqlite3 *ref = store_schema__reference();
    dm_str want = {0}, have = {0};
    int rc = ref ? store_schema__columns(ref, &want) : SQLITE_NOMEM;
    rc = rc == SQLITE_OK ? store_schema__columns(db, &have) : rc;
    sqlite3_close(ref);
    for (char *line = want.buf; rc == SQLITE_OK && !*table && line && *line;) {
        char *name = line + 1, *tab = strchr(name, '\t'), *end = strchr(tab, '\n');
        *tab = *end = '\0';
        char *col = tab + 1, *pair = dm_xasprintf("\t%s\t%s\n", name, col);
        char *prefix = dm_xasprintf("\t%s\t", name);
        if (!strstr(dm_str_get(&have), pair)) {
            *table = dm_xstrdup(name);
            *column = strstr(dm_str_get(&have), prefix) ? dm_xstrdup(col) : NULL;
        }
        free(pair);
        free(prefix);
        line = end + 1;
    }
    dm_str_free(&want);
    dm_str_free(&have);
    return rc;
}
