/* compare.h — the regression gate (docs/ci-gating.md): compare two runs configuration
 * by configuration and give each a verdict.
 *
 * Matching: configurations are matched by key; keys on one side only are
 * listed as added / removed and never fail the gate.
 * Environment: the fingerprint keys of run/env.h must be equal (with
 * counters_only only the driver part: renderer, gl_version, because a CPU
 * never changes a pipeline-statistics count); a difference is DM_ERR_ARG
 * unless allow_env_mismatch, which turns it into a warning.
 * Per matched configuration, in this order, the first failing check wins:
 *  - NEW failed where BASE was ok                          -> REGRESSION
 *  - a deterministic counter available on both sides differs by more than
 *    its relative tolerance (default: counts exact, floating derived
 *    counters COMPARE_DERIVED_EPS)                           -> REGRESSION
 *  - quality: PSNR dropped by more than psnr_drop dB, SSIM by more than
 *    ssim_drop, or the mean FLIP error rose by more than flip_rise (when
 *    both sides have FLIP) (not in counters_only mode)       -> REGRESSION
 *  - Instructions (group Cost, exact counts) available on both sides: the
 *    ratio new/base beyond 1 + threshold is REGRESSION, below 1 - threshold
 *    IMPROVEMENT, else PASS — decided without statistics; timing is then
 *    not gated (an exact count beats a noisy time).  InstructionsPerPixel
 *    is compared with the same threshold.  Also in counters_only mode.
 *  - time (not in counters_only mode): the percentile bootstrap CI (level,
 *    seeded per key) of median(new)/median(base) of the time counter and a
 *    Mann-Whitney U p-value, Benjamini-Hochberg adjusted over all timed
 *    configurations (q):
 *      lo > 1 + t and q < alpha                              -> REGRESSION
 *      hi < 1 - t and q < alpha                              -> IMPROVEMENT
 *      1 - t <= lo and hi <= 1 + t                           -> PASS
 *      otherwise                                             -> INCONCLUSIVE
 *    Identical samples on both sides give ratio = lo = hi = 1: PASS.
 *    Between runs (not in paired mode) the bounds are first divided by the
 *    machine interval [machine.lo, machine.hi] (compare_machine below): a
 *    REGRESSION needs lo / machine.hi > 1 + t, an IMPROVEMENT hi /
 *    machine.lo < 1 - t; a change the machine alone could explain is
 *    INCONCLUSIVE, its note naming the machine's change and the remedy.
 *    The samples are first blocked by round (models/blocking.h) unless
 *    no_blocking; lo_raw/hi_raw keep the CI of the raw samples.
 *    Every INCONCLUSIVE states `detectable`, the smallest change the data
 *    could have detected (the CI's half-width relative to the ratio), and
 *    the extra samples per side (rounds in paired mode) likely needed:
 *    n * f - n, n the smaller side's sample count, f the largest
 *    ((ratio - CI bound) / (ratio - threshold that bound must clear))^2
 *    over the CI sides that cross a threshold (a CI shrinks ~ 1/sqrt(n)).
 * Configurations failed on both sides are SKIPPED.  The suite geometric mean
 * of the timed ratios is reported.
 * Exit code of a comparison: 1 if any REGRESSION, else 3 if any
 * INCONCLUSIVE, else 0 (improvements pass).
 */
#ifndef GATE_COMPARE_H
#define GATE_COMPARE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "core/dm_results.h"
#include "core/dm_util.h"

/* Relative tolerance of a deterministic floating counter (a derived ratio):
 * two computations of one ratio from equal integer parts agree to a few
 * ULP (1e-16); any real change of a count moves a ratio by far more. */
#define COMPARE_DERIVED_EPS 1e-12

/* Worst first: the table is sorted by descending verdict. */
typedef enum compare_verdict {
    COMPARE_PASS = 0,
    COMPARE_SKIPPED,
    COMPARE_IMPROVEMENT,
    COMPARE_INCONCLUSIVE,
    COMPARE_REGRESSION,
} compare_verdict;

/* Between-run spread assumed when the runs themselves do not show more
 * (--run-spread).  A floor, not a measurement: one run per side cannot
 * estimate its between-run variance (Kalibera & Jones, ISMM 2013), and on
 * the shared machine this was written on the runs' own round spread was
 * larger every time (+-9..78 %; docs/ci-gating.md, "Timing between two
 * runs").  Set it from `dmbench compare` of two runs of one binary on
 * your runner. */
#define COMPARE_RUN_SPREAD 0.10
/* A change in WallTime / CPUTime between the runs beyond this is contention:
 * other processes took the CPU from ours (wall time moved, CPU time not). */
#define COMPARE_CONTENTION_TOL 0.05
/* A change of the 1-minute load average at least this large (and at least
 * a quarter of the CPU count) is a changed machine. */
#define COMPARE_LOAD_TOL 0.5
/* A change of the calibration workload's time (run/calibrate.h) beyond this
 * between BASE and NEW, or between a run's start and its end, is a machine
 * that itself ran at another speed.  About twice the workload's own spread
 * on a quiet machine (bench/calibrate.c: the largest deviation of 20
 * calibrations from their median was 6.7 % for the kernel and 4.7 % for
 * the draw; docs/ci-gating.md, "The calibration workload"), so that its
 * noise alone is not named. */
#define COMPARE_CALIB_TOL 0.15

/* What one run says about the machine it ran on. */
typedef struct compare_side_state {
    double load;             /* 1-minute load average at the run's start; NaN unknown */
    double wall_per_cpu;     /* median over configurations of median WallTime / median
                                CPUTime; NaN without CPUTime */
    double round_spread;     /* largest blocking_spread of a scene's round factors */
    size_t n_timed;          /* configurations with time samples */
    size_t n_precise_raw;    /* ... whose 95 % CI of the median is within +-3 % */
    size_t n_precise_blocked;/* ... the same after blocking by round */
    double ci_rel_raw, ci_rel_blocked;   /* median CI half-width / median, raw and blocked */
    double cal_cpu_ns;       /* calibration kernel, mean of the run's start and end; NaN none */
    double cal_draw_ns;      /* calibration draw, the same */
    double cal_drift;        /* largest |end / start - 1| of the two pieces; 0 unknown */
} compare_side_state;

/* The machine checks of a comparison: how far the machine alone may have
 * moved the times between BASE and NEW. */
typedef struct compare_machine {
    compare_side_state base, new_;
    double wall_ratio;       /* common mode: median over timed configurations of
                                median(NEW)/median(BASE) of the time counter; NaN none */
    double cpu_ratio;        /* the same for CPUTime; NaN without it */
    int contention;          /* wall_ratio / cpu_ratio beyond COMPARE_CONTENTION_TOL */
    int load_changed;        /* load averages differ by COMPARE_LOAD_TOL or more */
    double cal_ratio;        /* calibration kernel NEW / BASE; NaN when a side lacks it */
    double cal_draw_ratio;   /* calibration draw NEW / BASE; NaN when a side lacks it */
    int cal_changed;         /* either ratio beyond COMPARE_CALIB_TOL */
    double wall_per_cal;     /* wall_ratio / cal_ratio: the common mode once the machine's
                                own speed is divided out (shown, not used for verdicts) */
    double spread;           /* max(run_spread, both runs' round_spread) */
    double lo, hi;           /* machine interval: [1/(1+s), 1+s], widened to take in
                                wall_ratio when the machine changed; paired: [1, 1], or
                                the span of 1 and wall_ratio / cpu_ratio with contention
                                (a real change of the code moves CPU time too) */
    char *reason;            /* the checks in words, e.g. "WallTime x1.53 while CPUTime
                                x1.08 (contention); load average 0.70 -> 3.50" */
} compare_machine;

typedef struct compare_tolerance {
    const char *counter;
    double rel;              /* |new - base| <= rel * |base| passes */
} compare_tolerance;

/* Zero means default everywhere (see compare_defaults). */
typedef struct compare_desc {
    double time_threshold;   /* 0 -> 0.05 */
    double threshold;        /* Instructions: relative change that decides; 0 -> 0.005 */
    int paired;              /* samples are runs (rounds): notes say "rounds" */
    int replicated;          /* each side pooled from >= 2 separate runs (compare_load_paths):
                                samples are run minima as in paired mode, and the
                                between-run spread is in the data, not assumed */
    int instr_off;           /* set by compare_runs when the runs' CPUs differ: instruction
                                counts depend on the CPU (JIT target, libc ifuncs), so the
                                Cost counters are not compared (a warning says so) */
    double alpha;            /* 0 -> 0.01 */
    double level;            /* 0 -> 0.95 */
    double psnr_drop;        /* 0 -> 1.0 dB */
    double ssim_drop;        /* 0 -> 0.01 */
    double flip_rise;        /* 0 -> 0.005 (mean LDR-FLIP, docs/flip.md) */
    const char *time_counter;/* NULL -> "WallTime" */
    uint64_t seed;           /* bootstrap seed (0 is a valid seed) */
    int counters_only;
    int allow_env_mismatch;
    double run_spread;       /* 0 -> COMPARE_RUN_SPREAD: how far the machine's speed may move
                                between two runs when the runs show no more (compare_machine) */
    int no_blocking;         /* 1: the time CI of the raw samples, not blocked by round */
    const compare_tolerance *tolerances;
    size_t n_tolerances;
    /* 1 when `technique` names a built-in technique; NULL: every technique
     * is.  A configuration of any other technique (a user's GLSL file,
     * docs/user-techniques.md) whose key is on one side only is paired with
     * the configuration of identical parameters on the other side: its key
     * holds a hash of the file, so an edited shader changes the key, and the
     * pair is compared as the same configuration with its label saying the
     * source changed. */
    int (*builtin_technique)(const char *technique);
} compare_desc;

typedef struct compare_change {
    char *counter;
    double base, new_;
    char *note;              /* e.g. "unavailable on NEW"; NULL for a value change */
} compare_change;

typedef struct compare_item {
    char *key;
    char *label;             /* "mesh=plane technique=normal resolution=96x54" */
    char *name;              /* short: "plane@96x54/pom steps=32" (report_config_name) */
    compare_verdict verdict;
    char *note;              /* why (first failing check), NULL for a plain PASS */
    int timed;               /* the time statistics below are set */
    double ratio, lo, hi;    /* median(new)/median(base) and its CI (blocked by round) */
    double lo_raw, hi_raw;   /* the CI of the raw samples (= lo, hi when not blocked) */
    int blocked;             /* a side's samples were corrected by round */
    int machine_held;        /* the CI cleared the threshold but not the machine interval */
    double p, q;             /* Mann-Whitney p, BH-adjusted q */
    size_t n_base, n_new;
    double median_new;       /* NEW's median of the time counter, ns per frame; 0 when none (JUnit time) */
    double median_base;      /* BASE's, the same way */
    long extra_samples;      /* INCONCLUSIVE: per side; -1 unknown */
    double detectable;       /* timed: smallest relative change the data could detect (CI half-width / ratio) */
    int instr;               /* Instructions decided the verdict: */
    double instr_base, instr_new;   /* per frame on each side */
    compare_change *changes; /* deterministic counters that changed */
    size_t n_changes;
    int quality;             /* both sides have quality */
    double psnr_base, psnr_new, ssim_base, ssim_new;
    double flip_base, flip_new;   /* NaN where a side has no FLIP */
} compare_item;

typedef struct compare_result {
    compare_desc desc;       /* filled-in settings used */
    char *base_id, *new_id, *sweep;
    compare_item *items;     /* sorted worst first */
    size_t n_items;
    char **added, **removed; /* "label [key]" */
    size_t n_added, n_removed;
    char **env_diffs;        /* "cpu: 'A' vs 'B'" */
    size_t n_env_diffs;
    char **warnings;
    size_t n_warnings;
    size_t count[COMPARE_REGRESSION + 1];
    compare_machine machine; /* machine checks (timed comparisons) */
    double geomean;          /* NaN when no configuration was timed */
    size_t n_geomean;
} compare_result;

/* Fills the defaults of a zero desc field by field. */
compare_desc compare_defaults(const compare_desc *d);
/* Name of a verdict ("PASS", "REGRESSION", ...). */
const char *compare_verdict_name(compare_verdict v);

/* Compares NEW against BASE (both only read) into *out (zeroed first;
 * release with compare_result_free, also after a failure).  Returns 0 when
 * compared; DM_ERR_ARG with out->env_diffs listed when the fingerprints
 * differ and allow_env_mismatch is off; DM_ERR_ARG when the time counter is
 * GPUTime marked partial (never gated) — err says why. */
int compare_runs(const dm_run_result *base, const dm_run_result *new_, const compare_desc *d,
                 compare_result *out, dm_str *err);
/* --alpha: a significance level strictly between 0 and 1 (0 would never
 * call anything significant, >= 1 always).  0 or DM_ERR_RANGE (err). */
int compare_check_alpha(double alpha, dm_str *err);
/* --tolerance COUNTER=REL: COUNTER must be a known counter (err suggests
 * the closest).  0 or DM_ERR_UNKNOWN. */
int compare_check_tolerance_counter(const char *counter, dm_str *err);
/* A comparison without a single configuration in common compared nothing:
 * DM_ERR_ARG with the counts on each side in err; else 0. */
int compare_check_common(const compare_result *r, dm_str *err);
/* DM_EXIT_OK pass, DM_EXIT_FAILED regression, DM_EXIT_INCONCLUSIVE (see top). */
int compare_exit_code(const compare_result *r);
void compare_result_free(compare_result *r);

/* ---- outputs (compare_write.c) ---------------------------------------- */
/* Terminal table, worst first, then added/removed, warnings and a summary. */
void compare_write_text(const compare_result *r, FILE *f);
/* Markdown for a pull-request comment (compare_write_markdown):
 *   a headline: the verdict in words with the counts;
 *   the machine checks in one line when they held verdicts;
 *   a table of what changed only (not PASS): configuration (short name),
 *   base, new, ratio, CI, verdict, note;
 *   the PASS rows in a <details> block (none with only_changed);
 *   at most max_chars characters: rows that do not fit are cut, PASS rows
 *   first, with a line saying how many and where the rest is.
 * With none set, the Markdown of a comparison that did not happen (no
 * configuration in common, environments differ, a side could not be read):
 * the headline says so and why (reason; NULL: "no reason given"), with r's
 * environment differences and added/removed counts when r is not NULL, so
 * the CI step that posts it always has a file. */
#define COMPARE_MD_MAX 60000
typedef struct compare_md_desc {
    int only_changed;
    size_t max_chars;        /* 0 -> COMPARE_MD_MAX */
    int none;                /* nothing was compared, for `reason` */
    const char *reason;
} compare_md_desc;
/* Writes the Markdown d describes (NULL: every default) of r to path; JUnit
 * XML (one testcase per configuration: <failure> for REGRESSION, <skipped>
 * for INCONCLUSIVE and SKIPPED, the verdict in system-out); JSON
 * (everything in compare_result).  Each returns 0 or dm_write_file's
 * DM_ERR_IO / DM_ERR_DISK (errno says why) and writes atomically. */
int compare_write_markdown(const compare_result *r, const compare_md_desc *d, const char *path);
int compare_write_junit(const compare_result *r, const char *path);
int compare_write_json(const compare_result *r, const char *path);

/* ---- inputs (compare_input.c) ----------------------------------------- */
/* Loads one side: a results.json, a run directory (its results.json, or
 * the store beside it), or an output root holding `latest`.  Returns 0, or
 * DM_ERR_IO / DM_ERR_PARSE / DM_ERR_NOTFOUND with err naming the path. */
int compare_load_path(const char *path, dm_run_result *out, dm_str *err);
/* Loads run_id, or the newest run tagged tag, from the store at
 * store_path.  Same codes as above. */
int compare_load_store(const char *store_path, const char *run_id, const char *tag,
                       dm_run_result *out, dm_str *err);

/* ---- baselines (compare_input.c) --------------------------------------
 * Accepted baselines live in baselines.json beside the store:
 *   { "baselines": [ { "run": ID, "sweep": NAME, "reason": TEXT,
 *                      "accepted": ISO-8601 }, ... ] }  (append order). */
/* Path of baselines.json beside store_path (caller frees). */
char *compare_baselines_path(const char *store_path);
/* Appends an acceptance of run_id (which must exist in the store).
 * DM_ERR_NOTFOUND when absent, DM_ERR_ARG for an empty reason, DM_ERR_IO. */
int compare_baseline_accept(const char *store_path, const char *run_id, const char *reason,
                            dm_str *err);
/* Newest accepted baseline run id of that sweep (any sweep when NULL) into
 * *run_id (caller frees), with its reason into *reason (optional).
 * DM_ERR_NOTFOUND when none. */
int compare_baseline_latest(const char *store_path, const char *sweep, char **run_id,
                            char **reason, dm_str *err);

/* ---- paired mode (compare_paired.c) ----------------------------------- */
/* The fewest rounds per binary with which a paired timing verdict can be
 * reached at significance alpha: each round is one sample a side, and the
 * smallest two-sided p of the exact Mann-Whitney test with n a side is
 * 2 / C(2n, n) (every NEW sample above every BASE sample), which must fall
 * under alpha: 5 at the default 0.01 (2/252), 4 at 0.05.  Fewer can never
 * decide (only --counters-only can).  alpha outside (0, 1): the default. */
int compare_paired_min_rounds(double alpha);
/* Rounds when --rounds is not given: COMPARE_PAIRED_ROUNDS, or the
 * minimum above when that is more. */
#define COMPARE_PAIRED_ROUNDS 6
/* An INCONCLUSIVE note advises at most this many more samples or rounds;
 * past it the difference is below what the machine can resolve. */
#define COMPARE_ADVICE_MAX 100

typedef struct compare_paired_desc {
    const char *base_binary, *new_binary, *sweep_path;
    int rounds;              /* 0 -> COMPARE_PAIRED_ROUNDS; round r runs A,B when r is even, B,A when odd (ABBA) */
    int quiet;
} compare_paired_desc;
/* Runs the sweep `rounds` times with each binary, each run a fresh process
 * writing to its own temporary output directory (removed afterwards), and
 * pools each side's per-run minima per key across rounds into *base / *new_
 * (the run is the unit of replication: samples within one process are not
 * independent)
 * (deterministic counters, quality and status from the first round; a
 * configuration failed in any round is failed; a deterministic counter that
 * differs between rounds of one side is a warning in run->warnings).
 * Returns 0 or DM_ERR_CHILD (a run exited non-zero) / DM_ERR_IO. */
int compare_paired_run(const compare_paired_desc *d, dm_run_result *base, dm_run_result *new_,
                       dm_str *err);

/* ---- several separate runs per side (compare_paired.c) ------------------ */
/* Pools run r (the index-th of its side; 0 takes r as it is) into *pooled,
 * one minimum per run and key, as paired mode does; r is consumed. */
void compare_pool_run(dm_run_result *pooled, dm_run_result *r, int index);
/* Loads a comma-separated list of paths (dm_split_paths; each as
 * compare_load_path) and pools them with compare_pool_run; *n_runs is the
 * number of runs.  One path is loaded as it is (its samples kept).  A run
 * named twice (also under two names, `latest` and its id) is DM_ERR_ARG. */
int compare_load_paths(const char *list, dm_run_result *out, size_t *n_runs, dm_str *err);

#endif
