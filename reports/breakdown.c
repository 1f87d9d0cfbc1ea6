/* breakdown.c — which counter breakdown a scene's chart draws
 * (breakdown.h): pure functions of the run's counters and fits. */
#include "reports/breakdown.h"
#include "reports/report_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The models whose terms split frame time by stage; time-from-stages (over
 * the exact stage counters) is preferred to pipeline-linear (over
 * invocation counts) where a configuration has both. */
static const breakdown_stage breakdown__pl[] = {
    {"c0", NULL, "fixed"}, {"c_vs", "VSInvocations", "vertex"},
    {"c_tes", "TESInvocations", "tessellation"}, {"c_prim", "ClippingOutputPrimitives", "primitives"},
    {"c_px", "SamplesPassed", "pixels"} };
static const breakdown_stage breakdown__ts[] = {
    {"a", NULL, "fixed"}, {"b_geo", "GeometryInstructions", "geometry"},
    {"b_raster", "RasterInstructions", "raster"}, {"b_frag", "FragmentInstructions", "fragment"} };
static const breakdown_model breakdown__models[] = {
    {"time-from-stages", breakdown__ts, sizeof breakdown__ts / sizeof *breakdown__ts, 1},
    {"pipeline-linear", breakdown__pl, sizeof breakdown__pl / sizeof *breakdown__pl, 0} };
#define BREAKDOWN__N_MODELS (sizeof breakdown__models / sizeof *breakdown__models)

double breakdown_det_value(const dm_config_result *c, const char *name)
{
    const dm_counter_result *k = name ? dm_config_counter(c, name) : NULL;
    return k && k->available && k->deterministic && isfinite(k->value) ? k->value : 0;
}

static double breakdown__param(const dm_fit_result *f, const char *name)
{
    const dm_fit_param *p = dm_fit_param_find(f, name);
    return p ? p->value : NAN;
}

/* The fit of model m whose group matches c's params, any quality (NULL
 * when none); a model of the exact stage counters only where c has them. */
static const dm_fit_result *breakdown__fit_any(const dm_run_result *run, const dm_config_result *c,
                                               const breakdown_model *m)
{
    for (size_t k = 0; m->exact && k < m->n; k++)
        if (m->stages[k].counter && !(breakdown_det_value(c, m->stages[k].counter) > 0))
            return NULL;
    for (size_t i = 0; i < run->n_fits; i++) {
        const dm_fit_result *f = &run->fits[i];
        int match = f->model && strcmp(f->model, m->model) == 0 &&
                    isfinite(breakdown__param(f, m->stages[0].param));
        for (size_t g = 0; match && g < f->n_group; g++) {
            const char *v = dm_kv_get(c->params, c->n_params, f->group[g].key);
            match = v && strcmp(v, f->group[g].value) == 0;
        }
        if (match)
            return f;
    }
    return NULL;
}

const dm_fit_result *breakdown_fit(const dm_run_result *run, const dm_config_result *c,
                                   const breakdown_model *m)
{
    const dm_fit_result *f = breakdown__fit_any(run, c, m);
    return f && isfinite(f->r2) && f->r2 >= BREAKDOWN_MIN_STAGE_R2 ? f : NULL;
}

double breakdown_stage_ms(const breakdown_model *m, const dm_fit_result *f, const dm_config_result *c,
                          size_t k)
{
    double v = breakdown__param(f, m->stages[k].param);
    double n = m->stages[k].counter ? breakdown_det_value(c, m->stages[k].counter) : 1;
    return isfinite(v) ? v * n / 1e6 : 0;
}

double breakdown_measured_ms(const dm_config_result *c, size_t k)
{
    const dm_counter_result *g = dm_config_counter(c, "GeometryTime");
    const dm_counter_result *m = dm_config_counter(c, "MinimalShadingTime"), *w = report__frame_time(c);
    if (!g || !m || !w || !g->available || !m->available || !isfinite(g->median) || !isfinite(m->median))
        return NAN;
    double v = k == 0 ? g->median : k == 1 ? m->median - g->median : w->median - m->median;
    return fmax(0, v) / 1e6;
}

/* The key counters any of the n configurations has, into out. */
static size_t breakdown__key_counters(const dm_run_result *run, const size_t *rows, size_t n,
                                      const char *out[4])
{
    static const char *const want[] = {"VSInvocations", "TESInvocations", "ClippingOutputPrimitives",
                                       "FSInvocations", "SamplesPassed"};
    size_t m = 0;
    for (size_t k = 0; k < 5; k++) {
        int have = 0;
        for (size_t i = 0; i < n && !have; i++)
            have = breakdown_det_value(&run->configs[rows[i]], want[k]) > 0;
        if (have && !(k == 4 && m && strcmp(out[m - 1], "FSInvocations") == 0))
            out[m++] = want[k];   /* SamplesPassed only when FSInvocations is missing */
    }
    return m;
}

/* The first model with a fit good enough for one of the shown
 * configurations into b->fit; else the first with a poorer fit into
 * b->poor. */
static void breakdown__pick_model(const dm_run_result *run, breakdown *b)
{
    for (size_t j = 0; j < BREAKDOWN__N_MODELS && !b->fit; j++)
        for (size_t i = 0; i < b->n_bars && !b->fit; i++) {
            const dm_config_result *c = &run->configs[b->bars[i]];
            const dm_fit_result *any = breakdown__fit_any(run, c, &breakdown__models[j]);
            if (breakdown_fit(run, c, &breakdown__models[j]))
                b->fit = &breakdown__models[j];
            else if (any && !b->poor) {
                b->poor = &breakdown__models[j];
                b->poor_r2 = any->r2;
            }
        }
}

/* The tallest of each shown configuration's stack and median, ms. */
static double breakdown__hi(const dm_run_result *run, const breakdown *b)
{
    double hi = 0;
    for (size_t i = 0; i < b->n_bars; i++) {
        const dm_config_result *c = &run->configs[b->bars[i]];
        const dm_fit_result *f = b->fit ? breakdown_fit(run, c, b->fit) : NULL;
        double sum = 0;
        for (size_t k = 0; f && k < b->fit->n; k++)
            sum += breakdown_stage_ms(b->fit, f, c, k);
        for (size_t k = 0; b->kind == BREAKDOWN_MEASURED && k < BREAKDOWN_MEASURED_STAGES; k++) {
            double h = breakdown_measured_ms(c, k);
            sum += isfinite(h) ? h : 0;
        }
        hi = fmax(hi, fmax(sum, report__frame_time(c)->median / 1e6));
    }
    return hi;
}

void breakdown_choose(const dm_run_result *run, const size_t *rows, size_t n, breakdown *b)
{
    memset(b, 0, sizeof *b);
    b->poor_r2 = NAN;
    b->skipped = n > BREAKDOWN_MAX_BARS ? n - BREAKDOWN_MAX_BARS : 0;
    b->n_bars = n - b->skipped;
    b->bars = dm_xcalloc(b->n_bars + 1, sizeof *b->bars);
    memcpy(b->bars, rows + b->skipped, b->n_bars * sizeof *b->bars);
    int measured = 0;   /* the timed passes, measured, before any fit's estimate */
    for (size_t i = 0; i < b->n_bars && !measured; i++)
        measured = isfinite(breakdown_measured_ms(&run->configs[b->bars[i]], 0));
    if (measured)
        b->kind = BREAKDOWN_MEASURED;
    else
        breakdown__pick_model(run, b);
    if (b->fit)
        b->kind = BREAKDOWN_FIT;
    if (b->kind != BREAKDOWN_NONE) {
        b->poor = NULL, b->poor_r2 = NAN;
        b->hi_ms = breakdown__hi(run, b);
    } else if ((b->n_counters = breakdown__key_counters(run, b->bars, b->n_bars, b->counters)) > 0) {
        b->kind = BREAKDOWN_COUNTERS;
    }
    if (b->n_bars == 0)
        b->kind = BREAKDOWN_NONE;
}

void breakdown_free(breakdown *b)
{
    free(b->bars);
    memset(b, 0, sizeof *b);
}
