/* drift.c — the machine's drift removed from one scene's rounds (see drift.h). */
#include "models/drift.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "models/rng.h"
#include "models/stats.h"

/* Scratch of one fit: the fitted effects and a buffer for medians. */
typedef struct drift__fit {
    size_t nc, nr;
    const double *lx;        /* log samples, nc × nr, NaN = none */
    double *a, *b;           /* row levels (nc), round effects (nr; NaN = none) */
    double *tmp;             /* nc + nr + 1 values */
    double *loo;             /* nc × nr: the round's common mode without c (NaN: none) */
    struct drift__item *items;   /* nc + 1: a round's residuals, sorted */
} drift__fit;

/* A residual of a round and whose it is. */
typedef struct drift__item {
    double v;
    size_t c;
} drift__item;

static int drift__cmp_item(const void *pa, const void *pb)
{
    double a = ((const drift__item *)pa)->v, b = ((const drift__item *)pb)->v;
    return (a > b) - (a < b);
}

double drift_robust_sd(const double *v, size_t n)
{
    double *t = dm_xcalloc(n + 1, sizeof *t);
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(v[i]))
            t[m++] = v[i];
    double med = stats_median_inplace(t, m);
    for (size_t i = 0; i < m; i++)
        t[i] = fabs(t[i] - med);
    double sd = m >= 2 ? 1.4826 * stats_median_inplace(t, m) : NAN;
    free(t);
    return sd;
}

/* Root mean square of the finite values (the round effects are centred on
 * median 0): not robust on purpose, as a slow spell in fewer than half
 * the rounds is a drift, not an outlier.  NaN when none. */
static double drift__rms(const double *v, size_t n)
{
    double ss = 0;
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(v[i])) {
            ss += v[i] * v[i];
            m++;
        }
    return m ? sqrt(ss / (double)m) : NAN;
}

static double drift__cell(const drift__fit *f, size_t c, size_t r)
{
    return f->lx[c * f->nr + r];
}

/* Round effect b[r]: the median of log x - a over the round's configurations
 * other than skip ((size_t)-1: none), NaN with fewer than need of them. */
static double drift__round(const drift__fit *f, size_t r, size_t skip, size_t need)
{
    size_t m = 0;
    for (size_t c = 0; c < f->nc; c++)
        if (c != skip && isfinite(drift__cell(f, c, r)) && isfinite(f->a[c]))
            f->tmp[m++] = drift__cell(f, c, r) - f->a[c];
    return m >= need ? stats_median_inplace(f->tmp, m) : NAN;
}

/* Row level a[c]: the median over rounds of log x - b (0 for a round
 * without an effect). */
static double drift__level(const drift__fit *f, size_t c)
{
    size_t m = 0;
    for (size_t r = 0; r < f->nr; r++)
        if (isfinite(drift__cell(f, c, r)))
            f->tmp[m++] = drift__cell(f, c, r) - (isfinite(f->b[r]) ? f->b[r] : 0);
    return stats_median_inplace(f->tmp, m);
}

/* Every configuration's leave-one-out common mode of round r into
 * f->loo: the round's residuals sorted once, then the median of the other
 * m - 1 of them for each by index arithmetic (the drift__round with skip =
 * c of each, in O(m log m) for the round instead of O(m^2 log m)). */
static void drift__loo_round(drift__fit *f, size_t r)
{
    size_t m = 0;
    for (size_t c = 0; c < f->nc; c++) {
        f->loo[c * f->nr + r] = NAN;
        if (isfinite(drift__cell(f, c, r)) && isfinite(f->a[c]))
            f->items[m++] = (drift__item){ drift__cell(f, c, r) - f->a[c], c };
    }
    if (m < DRIFT_MIN_OTHERS + 1)
        return;
    qsort(f->items, m, sizeof *f->items, drift__cmp_item);
    size_t k = m - 1;   /* the others */
    for (size_t p = 0; p < m; p++) {
        /* t[i] = items[i] for i < p, items[i + 1] from p on */
        size_t i1 = (k - 1) / 2, i2 = k / 2;
        double v1 = f->items[i1 < p ? i1 : i1 + 1].v, v2 = f->items[i2 < p ? i2 : i2 + 1].v;
        f->loo[f->items[p].c * f->nr + r] = (v1 + v2) / 2;
    }
}

/* Median polish of log x = a[c] + b[r] + e by alternating medians, the
 * round effects centred on median 0 (so a is the level at the run's
 * median speed); stops when no effect moves by 1e-9 in log.  Returns the
 * number of rounds with an effect. */
static size_t drift__polish(drift__fit *f)
{
    for (size_t c = 0; c < f->nc; c++)
        f->a[c] = drift__level(f, c);
    size_t used = 0;
    for (int it = 0; it < DRIFT_POLISH_ITERS; it++) {
        double moved = 0;
        used = 0;
        for (size_t r = 0; r < f->nr; r++) {
            double nb = drift__round(f, r, (size_t)-1, DRIFT_MIN_CONFIGS);
            if (isfinite(nb))
                f->tmp[f->nc + used++] = nb;   /* tmp is large enough: see drift__fit_init */
            f->b[r] = nb;
        }
        double centre = stats_median_inplace(f->tmp + f->nc, used);
        for (size_t r = 0; r < f->nr; r++)
            if (isfinite(f->b[r]))
                f->b[r] -= centre;
        for (size_t c = 0; c < f->nc; c++) {
            double na = drift__level(f, c);
            if (isfinite(na) && isfinite(f->a[c]))
                moved = fmax(moved, fabs(na - f->a[c]));
            f->a[c] = na;
        }
        if (it > 0 && moved < 1e-9)
            break;
    }
    for (size_t r = 0; r < f->nr; r++)
        drift__loo_round(f, r);
    return used;
}

static void drift__fit_init(drift__fit *f, const double *lx, size_t nc, size_t nr)
{
    *f = (drift__fit){ .nc = nc, .nr = nr, .lx = lx };
    f->a = dm_xcalloc(nc + 1, sizeof *f->a);
    f->b = dm_xcalloc(nr + 1, sizeof *f->b);
    f->tmp = dm_xcalloc(nc + nr + 1, sizeof *f->tmp);
    f->loo = dm_xcalloc(nc * nr + 1, sizeof *f->loo);
    f->items = dm_xcalloc(nc + 1, sizeof *f->items);
}

static void drift__fit_free(drift__fit *f)
{
    free(f->a);
    free(f->b);
    free(f->tmp);
    free(f->loo);
    free(f->items);
}

/* The corrected log samples of configuration c into y[0..nr) (NaN where c
 * has none): log x less the round's common mode without c, where the
 * round has DRIFT_MIN_OTHERS other configurations; *n_corr counts those. */
static void drift__corrected(const drift__fit *f, size_t c, double *y, size_t *n_corr)
{
    *n_corr = 0;
    for (size_t r = 0; r < f->nr; r++) {
        double v = drift__cell(f, c, r), loo = NAN;
        if (isfinite(v))
            loo = f->loo[c * f->nr + r];
        y[r] = isfinite(loo) ? v - loo : v;
        *n_corr += isfinite(loo);
    }
}

/* The whole procedure on log samples lx: polish, correct, and each
 * configuration's corrected median (log) into med[c] (NaN: no sample).
 * Returns the rounds with a common mode. */
static size_t drift__procedure(const double *lx, size_t nc, size_t nr, double *med, double *y)
{
    drift__fit f;
    drift__fit_init(&f, lx, nc, nr);
    size_t used = drift__polish(&f);
    for (size_t c = 0; c < nc; c++) {
        size_t k, m = 0;
        drift__corrected(&f, c, y, &k);
        for (size_t r = 0; r < nr; r++)
            if (isfinite(y[r]))
                y[m++] = y[r];
        med[c] = stats_median_inplace(y, m);
    }
    drift__fit_free(&f);
    return used;
}

size_t drift_block_rounds(size_t n_rounds)
{
    long L = lround(cbrt((double)n_rounds));
    return L > 1 ? (size_t)L : 1;
}

/* A configuration's 95 % percentile intervals from the bootstrap (exp of
 * log quantiles); NaN where fewer than half the replicates are finite. */
typedef struct drift__ci {
    double lo, hi;           /* within the run: each replicate shifted back to the run's median speed */
    double blo, bhi;         /* between runs: the replicates as drawn */
} drift__ci;

/* 2.5 % and 97.5 % quantiles of the B log replicates v into *lo, *hi
 * (exp); NaN when fewer than half are finite. */
static void drift__percentiles(const double *v, size_t B, double *lo, double *hi)
{
    size_t m = 0;
    for (size_t b = 0; b < B; b++)
        m += isfinite(v[b]);
    *lo = m * 2 >= B ? exp(stats_quantile(v, B, 0.025)) : NAN;
    *hi = m * 2 >= B ? exp(stats_quantile(v, B, 0.975)) : NAN;
}

/* Percentile intervals of each configuration's bootstrap corrected
 * medians: replicates of the whole procedure on rounds drawn in blocks
 * (drift_block_rounds) with
 * replacement.  Within the run, each replicate is first shifted by the
 * median over configurations of its change from the point estimates pm
 * (log): where the run's median speed lies moves every configuration of
 * the scene alike and cancels in every comparison within the run.  Between
 * runs it does not cancel, so the unshifted replicates give ci[c].blo/bhi.
 * Returns the robust SD of the shifts (the uncertainty of the run's median
 * speed, log). */
static double drift__bootstrap(const drift_desc *d, const double *lx, const double *pm, drift__ci *ci)
{
    size_t nc = d->n_configs, nr = d->n_rounds, B = d->bootstrap > 0 ? (size_t)d->bootstrap : DRIFT_BOOTSTRAP_B;
    double *xs = dm_xcalloc(nc * nr + 1, sizeof *xs), *rep = dm_xcalloc(nc * B + 1, sizeof *rep);
    double *raw = dm_xcalloc(nc * B + 1, sizeof *raw), *shifts = dm_xcalloc(B + 1, sizeof *shifts);
    double *med = dm_xcalloc(nc + 1, sizeof *med), *y = dm_xcalloc(nr + nc + 1, sizeof *y);
    rng_state g = rng_seed(d->seed);
    size_t L = d->block ? d->block : drift_block_rounds(nr);
    for (size_t b = 0; b < B; b++) {
        for (size_t j = 0; j < nr;) {   /* blocks of L consecutive rounds, circular */
            size_t r = rng_below(&g, nr);
            for (size_t k = 0; k < L && j < nr; k++, j++)
                for (size_t c = 0; c < nc; c++)
                    xs[c * nr + j] = lx[c * nr + (r + k) % nr];
        }
        drift__procedure(xs, nc, nr, med, y);
        size_t m = 0;
        for (size_t c = 0; c < nc; c++)
            if (isfinite(med[c]) && isfinite(pm[c]))
                y[m++] = med[c] - pm[c];
        shifts[b] = stats_median_inplace(y, m);
        for (size_t c = 0; c < nc; c++) {
            rep[c * B + b] = med[c] - shifts[b];
            raw[c * B + b] = med[c];
        }
    }
    for (size_t c = 0; c < nc; c++) {
        drift__percentiles(rep + c * B, B, &ci[c].lo, &ci[c].hi);
        drift__percentiles(raw + c * B, B, &ci[c].blo, &ci[c].bhi);
    }
    double spread = drift_robust_sd(shifts, B);
    free(xs);
    free(rep);
    free(raw);
    free(shifts);
    free(med);
    free(y);
    return spread;
}

/* The noise figures of drift_result on the cells whose round has a common
 * mode without the configuration: raw, after that common mode, after the
 * calibration ratio. */
static void drift__noise(const drift_desc *d, const drift__fit *f, drift_result *out)
{
    size_t nc = f->nc, nr = f->nr, m = 0, mc = 0;
    double *raw = dm_xcalloc(nc * nr + 1, sizeof *raw), *loo = dm_xcalloc(nc * nr + 1, sizeof *loo);
    double *cal = dm_xcalloc(nc * nr + 1, sizeof *cal), *lc = dm_xcalloc(nr + 1, sizeof *lc);
    size_t nlc = 0;
    for (size_t r = 0; d->calib && r < nr; r++)
        if (isfinite(d->calib[r]) && d->calib[r] > 0)
            cal[nlc++] = log(d->calib[r]);
    double centre = stats_median_inplace(cal, nlc);
    for (size_t r = 0; r < nr; r++)
        lc[r] = d->calib && isfinite(d->calib[r]) && d->calib[r] > 0 ? log(d->calib[r]) - centre : NAN;
    for (size_t c = 0; c < nc; c++)
        for (size_t r = 0; r < nr; r++) {
            double v = drift__cell(f, c, r);
            double b = isfinite(v) ? f->loo[c * nr + r] : NAN;
            if (!isfinite(b) || !isfinite(f->a[c]))
                continue;
            raw[m] = v - f->a[c];
            loo[m++] = v - f->a[c] - b;
            if (isfinite(lc[r]))
                cal[mc++] = v - f->a[c] - lc[r];
        }
    out->raw_noise = drift_robust_sd(raw, m);
    out->loo_noise = drift_robust_sd(loo, m);
    out->calib_noise = mc >= 2 ? drift_robust_sd(cal, mc) : NAN;
    out->calib_spread = drift_robust_sd(lc, nr);
    double *per = dm_xcalloc(nr + 1, sizeof *per);   /* configurations in each round with an effect */
    size_t np = 0;
    for (size_t r = 0; r < nr; r++) {
        size_t k = 0;
        for (size_t c = 0; c < nc; c++)
            k += isfinite(drift__cell(f, c, r));
        if (isfinite(f->b[r]))
            per[np++] = (double)k;
    }
    double per_round = stats_median_inplace(per, np);
    /* a median of k values of SD s has SD about sqrt(pi/2) s / sqrt(k) */
    out->factor_noise = per_round > 0 ? sqrt(M_PI / 2) * out->loo_noise / sqrt(per_round) : NAN;
    out->helps = out->machine_spread > DRIFT_HELPS * out->factor_noise;
    free(per);
    free(raw);
    free(loo);
    free(cal);
    free(lc);
}

/* The raw figures of every configuration (models/stats.h). */
static void drift__raw(const drift_desc *d, drift_result *out, size_t *with_samples)
{
    *with_samples = 0;
    for (size_t c = 0; c < d->n_configs; c++) {
        drift_config *k = &out->configs[c];
        stats_summary su;
        *k = (drift_config){ .raw_median = NAN, .raw_lo = NAN, .raw_hi = NAN,
                             .median = NAN, .lo = NAN, .hi = NAN, .between_lo = NAN, .between_hi = NAN };
        if (stats_summarize(d->x + c * d->n_rounds, d->n_rounds, d->seed + c, &su) == 0) {
            k->n = su.n;
            k->raw_median = su.median;
            k->raw_lo = su.ci_lo;
            k->raw_hi = su.ci_hi;
            (*with_samples)++;
        }
    }
}

/* The corrected figures of every configuration from the point fit f:
 * within the run, the hull of the corrected samples' own CI and the
 * shifted bootstrap interval; between runs, that hull and the unshifted
 * interval.  Sets out->reference_spread.  With d->point_only the
 * bootstrap is skipped: the CI is the samples' own, the between-run one
 * NaN. */
static void drift__point(const drift_desc *d, const drift__fit *f, const double *lx, drift_result *out)
{
    size_t nc = d->n_configs, nr = d->n_rounds;
    drift__ci *ci = dm_xcalloc(nc + 1, sizeof *ci);
    double *y = dm_xcalloc(nr + 1, sizeof *y), *pm = dm_xcalloc(nc + 1, sizeof *pm);
    if (!d->point_only) {
        drift__procedure(lx, nc, nr, pm, y);
        out->reference_spread = drift__bootstrap(d, lx, pm, ci);
    }
    for (size_t c = 0; c < nc; c++) {
        drift_config *k = &out->configs[c];
        drift__corrected(f, c, y, &k->n_corrected);
        for (size_t r = 0; r < nr; r++)
            y[r] = exp(y[r]);   /* NaN stays NaN */
        stats_summary su;
        if (k->n == 0 || stats_summarize(y, nr, d->seed + c, &su) != 0)
            continue;
        k->median = su.median;
        if (d->point_only) {
            k->lo = su.ci_lo;
            k->hi = su.ci_hi;
            continue;
        }
        k->lo = isfinite(ci[c].lo) ? fmin(su.ci_lo, ci[c].lo) : NAN;
        k->hi = isfinite(ci[c].hi) ? fmax(su.ci_hi, ci[c].hi) : NAN;
        k->between_lo = isfinite(k->lo) && isfinite(ci[c].blo) ? fmin(k->lo, ci[c].blo) : NAN;
        k->between_hi = isfinite(k->hi) && isfinite(ci[c].bhi) ? fmax(k->hi, ci[c].bhi) : NAN;
    }
    free(ci);
    free(y);
    free(pm);
}

int drift_correct(const drift_desc *d, drift_result *out)
{
    memset(out, 0, sizeof *out);
    if (!d->x || d->n_configs == 0 || d->n_rounds == 0)
        return DM_ERR_ARG;
    size_t nc = d->n_configs, nr = d->n_rounds, with = 0;
    out->configs = dm_xcalloc(nc + 1, sizeof *out->configs);
    out->round_factor = dm_xcalloc(nr + 1, sizeof *out->round_factor);
    out->machine_spread = out->raw_noise = out->loo_noise = out->calib_noise = out->calib_spread = NAN;
    out->reference_spread = out->half_shift = NAN;
    drift__raw(d, out, &with);
    double *lx = dm_xcalloc(nc * nr + 1, sizeof *lx);
    for (size_t i = 0; i < nc * nr; i++)
        lx[i] = isfinite(d->x[i]) && d->x[i] > 0 ? log(d->x[i]) : NAN;
    drift__fit f;
    drift__fit_init(&f, lx, nc, nr);
    out->n_rounds_used = with >= DRIFT_MIN_CONFIGS ? drift__polish(&f) : 0;
    for (size_t r = 0; r < nr; r++)
        out->round_factor[r] = out->n_rounds_used ? exp(f.b[r]) : NAN;
    if (with < DRIFT_MIN_CONFIGS)
        out->why = "fewer than 3 configurations with samples in the scene: no common mode to measure";
    else if (out->n_rounds_used < DRIFT_MIN_ROUNDS)
        out->why = "fewer than 3 rounds with 3 configurations sampled: too few to measure the common mode";
    if (!out->why) {
        out->machine_spread = drift__rms(f.b, nr);
        drift__noise(d, &f, out);
        drift__point(d, &f, lx, out);
        out->half_shift = drift_half_shift(out->round_factor, nr);
        out->corrected = 1;
    }
    drift__fit_free(&f);
    free(lx);
    return 0;
}

double drift_half_shift(const double *round_factor, size_t n_rounds)
{
    double *v = dm_xcalloc(n_rounds + 1, sizeof *v);
    size_t m = 0;
    for (size_t r = 0; r < n_rounds; r++)
        if (isfinite(round_factor[r]) && round_factor[r] > 0)
            v[m++] = log(round_factor[r]);
    double h = NAN;
    if (m >= 2 * DRIFT_MIN_ROUNDS) {
        size_t half = m / 2;
        double late = stats_median_inplace(v + m - half, half);   /* before the earlier half is reordered */
        h = late - stats_median_inplace(v, half);
    }
    free(v);
    return h;
}

void drift_result_free(drift_result *r)
{
    free(r->round_factor);
    free(r->configs);
    memset(r, 0, sizeof *r);
}
