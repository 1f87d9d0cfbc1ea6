/* protocol.c — the measuring decisions as pure functions (see protocol.h). */
#include "protocol.h"
#include "models/drift.h"
#include "models/stats.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>

void protocol_defaults(protocol_desc *d)
{
    if (d->warmup_agree <= 0)
        d->warmup_agree = PROTOCOL_WARMUP_AGREE;
    if (d->warmup_tries <= 0)
        d->warmup_tries = PROTOCOL_WARMUP_TRIES;
    if (d->max_frames <= 0)
        d->max_frames = PROTOCOL_MAX_FRAMES;
    if (d->drift_limit <= 0)
        d->drift_limit = PROTOCOL_DRIFT_LIMIT;
    if (d->drift_t <= 0)
        d->drift_t = PROTOCOL_DRIFT_T;
}

void protocol_desc_from_measure(protocol_desc *d, const sweep_measure *m, uint64_t seed)
{
    *d = (protocol_desc){ .warmup_frames = m->warmup_frames, .frames_per_sample = m->frames_per_sample,
                          .min_sample_ms = m->min_sample_ms, .samples_min = m->samples_min,
                          .samples_max = m->samples_max, .target_ci = m->target_ci,
                          .max_seconds = m->max_seconds, .seed = seed };
    protocol_defaults(d);
}

/* ---- warm-up ---------------------------------------------------------------- */

int protocol_warmup_begin(const protocol_desc *d, protocol_warmup *w)
{
    (void)d;
    *w = (protocol_warmup){ .stage = PROTOCOL_WARMUP_FIRST };
    return 1;
}

int protocol_warmup_frames(const protocol_desc *d, double frame_ns)
{
    int k = d->frames_per_sample > 0 ? d->frames_per_sample : 1;
    if (d->min_sample_ms <= 0 || !(frame_ns > 0))
        return k;
    double want = ceil(d->min_sample_ms * 1e6 / frame_ns);
    return want < 1 ? 1 : want > k ? k : (int)want;
}

/* Ends the warm-up on the frame time prev_ns. */
static int protocol__settle(protocol_warmup *w, int agreed)
{
    w->agreed = agreed;
    w->settled_ns = w->prev_ns;
    w->stage = PROTOCOL_WARMUP_DONE;
    return 0;
}

/* The first frame is timed alone because llvmpipe JIT-compiles a program's
 * variant at its first draw (also when the program came from the binary
 * cache); the frames after it give the frame time that sizes the agreement
 * samples. */
int protocol_warmup_next(const protocol_desc *d, protocol_warmup *w, double frame_ns)
{
    switch (w->stage) {
    case PROTOCOL_WARMUP_FIRST:
        w->first_ns = w->rest_ns = frame_ns;
        if (d->warmup_frames > 1) {
            w->stage = PROTOCOL_WARMUP_REST;
            return d->warmup_frames - 1;
        }
        break;
    case PROTOCOL_WARMUP_REST:
        w->rest_ns = frame_ns;
        break;
    case PROTOCOL_WARMUP_AGREE_STAGE:
        if (w->n_agree++ > 0 && fabs(frame_ns - w->prev_ns) <= d->warmup_agree * w->prev_ns)
            return protocol__settle(w, 1);
        w->prev_ns = frame_ns;
        return w->n_agree > d->warmup_tries ? protocol__settle(w, 0) : w->sample_frames;
    case PROTOCOL_WARMUP_DONE:
        return 0;
    }
    w->stage = PROTOCOL_WARMUP_AGREE_STAGE;
    w->sample_frames = protocol_warmup_frames(d, w->rest_ns);
    return w->sample_frames;
}

/* ---- timing samples ------------------------------------------------------------ */

/* Short samples measure the scheduler more than the frame: enough frames
 * to last min_sample_ms (as Google Benchmark grows its iteration count). */
int protocol_sample_frames(const protocol_desc *d, double frame_ns)
{
    double want = d->min_sample_ms * 1e6 / (frame_ns > 1 ? frame_ns : 1);
    int frames = want > d->frames_per_sample ? (int)ceil(want) : d->frames_per_sample;
    int cap = d->max_frames > 0 ? d->max_frames : PROTOCOL_MAX_FRAMES;
    return frames > cap ? cap : frames;
}

/* Least-squares fit of the finite x[i] against i: slope, its standard
 * error and the count used.  se is 0 when the points lie on a line. */
static size_t protocol__trend(const double *x, size_t n, double *slope, double *se)
{
    double si = 0, sx = 0;
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i])) {
            si += (double)i;
            sx += x[i];
            m++;
        }
    if (m < 4)
        return m;
    double mi = si / m, mx = sx / m, sii = 0, six = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i])) {
            sii += ((double)i - mi) * ((double)i - mi);
            six += ((double)i - mi) * (x[i] - mx);
        }
    *slope = six / sii;
    double rss = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i])) {
            double r = x[i] - mx - *slope * ((double)i - mi);
            rss += r * r;
        }
    *se = sqrt(rss / (double)(m - 2) / sii);
    return m;
}

int protocol_drift(const protocol_desc *d, const double *x, size_t n, double *drift)
{
    double slope = 0, se = 0, limit = d->drift_limit > 0 ? d->drift_limit : PROTOCOL_DRIFT_LIMIT;
    double tmin = d->drift_t > 0 ? d->drift_t : PROTOCOL_DRIFT_T;
    *drift = NAN;
    if (!x || protocol__trend(x, n, &slope, &se) < 4)
        return 0;
    double med = stats_median(x, n);
    if (!(med != 0))
        return 0;
    *drift = slope * (double)(n - 1) / fabs(med);
    double t = se > 0 ? fabs(slope) / se : slope != 0 ? INFINITY : 0;
    return fabs(*drift) > limit && t > tmin;
}

protocol_decision protocol_decide(const protocol_desc *d, const double *x, size_t n, double elapsed_s)
{
    protocol_decision r = { .stop = PROTOCOL_CONTINUE, .ci_rel = NAN, .drift = NAN };
    stats_summary su;
    if (x && stats_summarize(x, n, d->seed, &su) == 0)
        r.ci_rel = su.ci_rel;
    int enough = n >= (size_t)d->samples_min;
    if (!x)
        r.stop = PROTOCOL_NO_STOP_COUNTER;
    else if (enough && r.ci_rel <= d->target_ci)
        r.stop = PROTOCOL_CONVERGED;
    else if (enough && elapsed_s > d->max_seconds)
        r.stop = PROTOCOL_TIME_CAP;
    else if (n >= (size_t)d->samples_max)
        r.stop = PROTOCOL_MAX_SAMPLES;
    r.drifting = protocol_drift(d, x, n, &r.drift);
    return r;
}

const char *protocol_stop_name(protocol_stop s)
{
    switch (s) {
    case PROTOCOL_CONTINUE: return "continue";
    case PROTOCOL_CONVERGED: return "converged";
    case PROTOCOL_TIME_CAP: return "time cap";
    case PROTOCOL_MAX_SAMPLES: return "max samples";
    case PROTOCOL_NO_STOP_COUNTER: return "no stop counter";
    }
    return "?";
}

size_t protocol_resume_limit(const protocol_desc *d)
{
    return d->samples_max > 1 ? (size_t)d->samples_max - 1 : 0;
}

/* ---- extra rounds (--extra-time) ---------------------------------------------- */

/* 1 when configuration a goes before b: the larger CI first, an unknown
 * (NaN) one before every known one, equal ones by index. */
static int protocol__noisier(const double *ci_rel, size_t a, size_t b)
{
    int na = isnan(ci_rel[a]), nb = isnan(ci_rel[b]);
    if (na != nb)
        return na;
    if (!na && ci_rel[a] != ci_rel[b])
        return ci_rel[a] > ci_rel[b];
    return a < b;
}

size_t protocol_extra_round(const double *ci_rel, const double *sample_s, size_t n, double target_ci,
                            double budget_s, size_t *pick, protocol_extra_why *why)
{
    size_t short_of = 0;
    for (size_t i = 0; i < n; i++) {
        if (ci_rel[i] <= target_ci)
            continue;
        size_t k = short_of++;   /* insertion: n is a scene's configurations */
        for (; k > 0 && protocol__noisier(ci_rel, i, pick[k - 1]); k--)
            pick[k] = pick[k - 1];
        pick[k] = i;
    }
    size_t taken = 0;
    double spent = 0;
    for (size_t k = 0; k < short_of; k++) {
        double s = sample_s[pick[k]];
        if (!(s >= 0) || !isfinite(s) || !(spent + s <= budget_s))
            continue;
        spent += s;
        pick[taken++] = pick[k];
    }
    *why = taken ? PROTOCOL_EXTRA_MORE : short_of ? PROTOCOL_EXTRA_BUDGET : PROTOCOL_EXTRA_REACHED;
    return taken;
}

int protocol_extra_corrected(const double *x, size_t n_configs, size_t n_rounds, uint64_t seed,
                             double *ci_rel)
{
    for (size_t c = 0; c < n_configs; c++)
        ci_rel[c] = NAN;
    drift_result d;
    if (drift_correct(&(drift_desc){ .n_configs = n_configs, .n_rounds = n_rounds, .x = x, .seed = seed,
                                     .point_only = 1 }, &d) != 0)
        return 0;
    int removed = d.corrected && d.helps;   /* as run/precision.c keeps it */
    for (size_t c = 0; removed && c < n_configs; c++) {
        const drift_config *k = &d.configs[c];
        if (isfinite(k->median) && k->median > 0 && isfinite(k->lo) && isfinite(k->hi))
            ci_rel[c] = (k->hi - k->lo) / 2 / k->median;
    }
    drift_result_free(&d);
    return removed;
}

int protocol_extra_clearly_within(double corrected_ci_rel, double target_ci)
{
    return corrected_ci_rel <= PROTOCOL_EXTRA_CLEAR * target_ci;   /* NaN: not known, not within */
}

int protocol_extra_done(double raw_ci_rel, double corrected_ci_rel, double target_ci)
{
    return isfinite(corrected_ci_rel) ? protocol_extra_clearly_within(corrected_ci_rel, target_ci)
                                      : raw_ci_rel <= target_ci;
}

const char *protocol_extra_why_name(protocol_extra_why w)
{
    switch (w) {
    case PROTOCOL_EXTRA_MORE: return "more rounds planned";
    case PROTOCOL_EXTRA_REACHED: return "targets reached";
    case PROTOCOL_EXTRA_BUDGET: return "budget spent";
    }
    return "?";
}

/* ---- --budget ------------------------------------------------------------------ */

/* The image renders and the warm-up's agreement samples are counted as
 * 12 samples of K frames plus 20 frames. */
double protocol_predict_s(const protocol_desc *d, double frame_ns)
{
    int path = d->path_frames > 0;
    double sample = frame_ns * (path ? d->path_frames : d->frames_per_sample);
    if (!path && sample < d->min_sample_ms * 1e6)
        sample = d->min_sample_ms * 1e6;
    /* the stop rule: after the sample that takes the sampling past
     * max_seconds, but not before samples_min nor after samples_max */
    double n = sample > 0 ? floor(d->max_seconds * 1e9 / sample) + 1 : d->samples_max;
    n = n < d->samples_min ? d->samples_min : n > d->samples_max ? d->samples_max : n;
    double sampling = n * sample;
    double untimed = d->warmup_frames + 12.0 * d->frames_per_sample + 20 + (path ? d->path_frames : 0);
    return (sampling + frame_ns * untimed) / 1e9;
}

void protocol_desc_on_path(protocol_desc *d, size_t frames)
{
    d->path_frames = frames > INT_MAX ? INT_MAX : (int)frames;   /* the axis stops at 100 000 */
}

double protocol_eta_s(double prior_s, size_t done, double elapsed_s, size_t left, size_t total)
{
    if (done == 0 || left == 0 || (double)done < 0.1 * (double)total ||
        !(elapsed_s >= PROTOCOL_ETA_MIN_S))
        return NAN;
    double k = prior_s > 0 && isfinite(prior_s) ? PROTOCOL_ETA_PRIOR : 0;
    double rate = (elapsed_s + k * (k > 0 ? prior_s : 0)) / ((double)done + k);
    return rate * (double)left;
}
