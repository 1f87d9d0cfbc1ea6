/* recommend.c — the pick per scene (see recommend.h for the rules). */
#include "reports/recommend.h"

#include "core/dm_util.h"

#include <math.h>
#include <stdlib.h>

static int recommend__usable(const recommend_point *p)
{
    return isfinite(p->time) && isfinite(p->error);
}

/* 1 when a comes before b: lower median, then lower error, then index. */
static int recommend__before(const recommend_point *p, size_t a, size_t b)
{
    if (p[a].time != p[b].time)
        return p[a].time < p[b].time;
    if (p[a].error != p[b].error)
        return p[a].error < p[b].error;
    return a < b;
}

/* Indices of the usable points with (family mask) fastest first into out;
 * returns how many.  Insertion sort: a scene has tens of points. */
static size_t recommend__sorted(const recommend_point *p, size_t n, unsigned mask, size_t *out)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        if (!recommend__usable(&p[i]) || !(mask & 1u << p[i].family))
            continue;
        size_t b = m++;
        while (b > 0 && recommend__before(p, i, out[b - 1])) {
            out[b] = out[b - 1];
            b--;
        }
        out[b] = i;
    }
    return m;
}

/* The epsilon front of the points selected by mask (recommend_front). */
static size_t recommend__front_of(const recommend_point *p, size_t n, unsigned mask, double eps,
                                  size_t *front)
{
    size_t m = recommend__sorted(p, n, mask, front), k = 0;
    double best = INFINITY;
    for (size_t i = 0; i < m; i++)
        if (p[front[i]].error < best - eps) {
            best = p[front[i]].error;
            front[k++] = front[i];
        }
    return k;
}

size_t recommend_front(const recommend_point *p, size_t n, double epsilon, size_t *front)
{
    return recommend__front_of(p, n, ~0u, epsilon, front);
}

/* Families eligible for a pick: the lit ones, or all when no lit point is usable. */
static unsigned recommend__eligible_mask(const recommend_point *p, size_t n, int *lit_only)
{
    unsigned lit = ~0u & ~(1u << RECOMMEND_UNLIT);
    for (size_t i = 0; i < n; i++)
        if (recommend__usable(&p[i]) && p[i].family != RECOMMEND_UNLIT) {
            *lit_only = 1;
            return lit;
        }
    *lit_only = 0;
    return ~0u;
}

/* The smallest round value (1, 2, 5 × 10^k) at or above v. */
static double recommend__round_up(double v)
{
    double decade = pow(10, floor(log10(v))), m = v / decade;
    if (m > 5 * (1 + 1e-12))
        return 10 * decade;
    return (m <= 1 * (1 + 1e-12) ? 1 : m <= 2 * (1 + 1e-12) ? 2 : 5) * decade;
}

/* The next round value above the round value r. */
static double recommend__next_round(double r)
{
    return recommend__round_up(r * 1.5);
}

/* The eligible times of a scene: the points' median times, usable, of the
 * families in mask, positive. */
typedef struct recommend__times {
    const recommend_point *p;
    size_t n;
    unsigned mask;
} recommend__times;

static int recommend__counts(const recommend__times *t, size_t i)
{
    const recommend_point *q = &t->p[i];
    return recommend__usable(q) && (t->mask & 1u << q->family) && q->time > 0;
}

/* The eligible times fastest first: indices into s (capacity n); count. */
static size_t recommend__times_sorted(const recommend__times *t, size_t *s)
{
    size_t m = recommend__sorted(t->p, t->n, t->mask, s), k = 0;
    for (size_t i = 0; i < m; i++)
        if (recommend__counts(t, s[i]))
            s[k++] = s[i];
    return k;
}

/* The roundest value in [a, b], nearest √(a b) on a log scale: a 1, 2 or
 * 5 × 10^k first, then one significant digit, then two, then three, else
 * √(a b) itself. */
static double recommend__roundest(double a, double b)
{
    double mid = sqrt(a * b), best = NAN;
    for (double c = recommend__round_up(a); c <= b * (1 + 1e-12); c = recommend__next_round(c))
        if (isnan(best) || fabs(log(c / mid)) < fabs(log(best / mid)))
            best = c;
    for (int digits = 1; digits <= 3 && isnan(best); digits++) {
        double step = pow(10, floor(log10(b)) - digits + 1);
        for (double c = ceil(a / step * (1 - 1e-12)) * step; c <= b * (1 + 1e-12); c += step)
            if (isnan(best) || fabs(log(c / mid)) < fabs(log(best / mid)))
                best = c;
    }
    return isnan(best) ? mid : best;
}

/* The budget of gap g of the k sorted times s (between s[g] and s[g + 1]):
 * the roundest value in its middle half on a log scale, so that it stands
 * at least a quarter of the gap from both; g = k - 1: every time admitted,
 * the round value at or above the slowest × RECOMMEND_NOISE. */
static double recommend__gap_budget(const recommend_point *p, const size_t *s, size_t k, size_t g)
{
    if (g + 1 >= k)
        return recommend__round_up(p[s[k - 1]].time * RECOMMEND_NOISE);
    double lo = p[s[g]].time, hi = p[s[g + 1]].time, q = pow(hi / lo, 0.25);
    return recommend__roundest(lo * q, hi / q);
}

/* The gap the default budget sits in (recommend.h): the widest on a log
 * scale, wider than 2 log RECOMMEND_NOISE; equal widths to the one whose
 * count under it is nearest half, then to the lower; k - 1 (every time
 * admitted) when no gap is that wide. */
static size_t recommend__gap_of(const recommend_point *p, const size_t *s, size_t k)
{
    size_t best = k - 1;
    double best_w = 2 * log(RECOMMEND_NOISE), best_split = INFINITY, half = (double)k / 2;
    for (size_t g = 0; g + 1 < k; g++) {
        double w = log(p[s[g + 1]].time / p[s[g]].time), split = fabs((double)(g + 1) - half);
        if (w > best_w + 1e-9 || (best + 1 < k && fabs(w - best_w) <= 1e-9 && split < best_split)) {
            best = g;
            best_w = w;
            best_split = split;
        }
    }
    return best;
}

double recommend_default_budget(const recommend_point *p, size_t n)
{
    int lit_only;
    recommend__times t = {p, n, recommend__eligible_mask(p, n, &lit_only)};
    size_t *s = dm_xcalloc(n + 1, sizeof *s), k = recommend__times_sorted(&t, s);
    double b = k > 0 ? recommend__gap_budget(p, s, k, recommend__gap_of(p, s, k)) : 0;
    free(s);
    return b;
}

static int recommend__ci_known(const recommend_point *p)
{
    return isfinite(p->ci_lo) && isfinite(p->ci_hi);
}

/* The best point within the budget on the epsilon front of mask (NONE). */
static size_t recommend__best_within(const recommend_point *p, size_t n, unsigned mask, double eps,
                                     double budget, size_t *scratch)
{
    size_t m = recommend__front_of(p, n, mask, eps, scratch), best = RECOMMEND_NONE;
    for (size_t i = 0; i < m && p[scratch[i]].time <= budget; i++)
        best = scratch[i];
    return best;
}

/* A point of equal quality (within eps) to the pick, within the budget and
 * eligible, whose time CI overlaps the pick's or whose median is within
 * resolvable (relative) of the pick's: the data cannot tell which is
 * cheaper.  NONE when there is none. */
static size_t recommend__tie_of(const recommend_point *p, size_t n, unsigned mask, double eps,
                                double resolvable, double budget, size_t pick)
{
    const recommend_point *a = &p[pick];
    for (size_t i = 0; i < n && recommend__ci_known(a); i++) {
        const recommend_point *b = &p[i];
        if (i == pick || !recommend__usable(b) || !(mask & 1u << b->family) || b->time > budget ||
            !recommend__ci_known(b) || fabs(b->error - a->error) >= eps)
            continue;
        int overlap = b->ci_lo <= a->ci_hi && a->ci_lo <= b->ci_hi;
        int unresolved = resolvable > 0 && fabs(b->time - a->time) <= resolvable * a->time;
        if (recommend__before(p, pick, i) && (overlap || unresolved))
            return i;
    }
    return RECOMMEND_NONE;
}

/* 1 when a is named before b of a tie (recommend.h): the simpler pipeline
 * (fragment, vertex, tessellation), then the points' order. */
static int recommend__named_first(const recommend_point *p, size_t a, size_t b)
{
    return p[a].family != p[b].family ? p[a].family < p[b].family : a < b;
}

/* The knee of the eligible front (recommend.h); NONE without a bend. */
static size_t recommend__knee_of(const recommend_point *p, const size_t *front, size_t m)
{
    if (m < 3 || !(p[front[0]].time > 0))
        return RECOMMEND_NONE;
    double x0 = log(p[front[0]].time), x1 = log(p[front[m - 1]].time);
    double y0 = p[front[0]].error, y1 = p[front[m - 1]].error;
    if (!(x1 > x0) || !(y0 > y1))
        return RECOMMEND_NONE;
    size_t knee = RECOMMEND_NONE;
    double far = 0;
    for (size_t i = 1; i + 1 < m; i++) {
        double x = (log(p[front[i]].time) - x0) / (x1 - x0);
        double y = (p[front[i]].error - y1) / (y0 - y1);
        double below = 1 - x - y;   /* distance to the line x + y = 1, times √2 */
        if (below > far)
            far = below, knee = front[i];
    }
    return knee;
}

/* The near miss (recommend.h): eligible, median over the budget, CI low
 * end within it, error below the pick's by more than eps; the best error,
 * then the lower median.  NONE when there is none. */
static size_t recommend__near_miss_of(const recommend_point *p, size_t n, unsigned mask, double eps,
                                      double budget, size_t pick)
{
    size_t best = RECOMMEND_NONE;
    for (size_t i = 0; i < n; i++) {
        const recommend_point *q = &p[i];
        if (!recommend__usable(q) || !(mask & 1u << q->family) || !(q->time > budget) ||
            !recommend__ci_known(q) || !(q->ci_lo <= budget))
            continue;
        if (pick != RECOMMEND_NONE && !(q->error < p[pick].error - eps))
            continue;
        if (best == RECOMMEND_NONE || q->error < p[best].error ||
            (q->error == p[best].error && q->time < p[best].time))
            best = i;
    }
    return best;
}

/* The low and high ends of a point's time CI (its median when unknown). */
static double recommend__lo(const recommend_point *p)
{
    return isfinite(p->ci_lo) && p->ci_lo > 0 ? fmin(p->ci_lo, p->time) : p->time;
}

static double recommend__hi(const recommend_point *p)
{
    return isfinite(p->ci_hi) ? fmax(p->ci_hi, p->time) : p->time;
}

/* Whether the default budget could sit elsewhere with the times anywhere in
 * their CIs (recommend_result.budget_moves): the chosen gap at its
 * narrowest (its lower time at its CI's high end, its upper at its low
 * end) against each other gap at its widest, and against admitting every
 * time (2 log RECOMMEND_NOISE); the widest such rival whose budget changes
 * the pick is the one reported. */
static void recommend__budget_check(const recommend_point *p, size_t n, const recommend_desc *d,
                                    recommend_result *out)
{
    int lit_only;
    recommend__times t = {p, n, recommend__eligible_mask(p, n, &lit_only)};
    size_t *s = dm_xcalloc(n + 1, sizeof *s), k = recommend__times_sorted(&t, s);
    size_t g = k > 0 ? recommend__gap_of(p, s, k) : 0;
    double floor_w = 2 * log(RECOMMEND_NOISE);
    double narrowest = g + 1 < k ? log(recommend__lo(&p[s[g + 1]]) / recommend__hi(&p[s[g]])) : floor_w;
    double rival_w = -INFINITY;
    for (size_t j = 0; j < k; j++) {   /* j = k - 1: every time admitted */
        double w = j + 1 < k ? log(recommend__hi(&p[s[j + 1]]) / recommend__lo(&p[s[j]])) : floor_w;
        if (j == g || (j + 1 < k && !(w > floor_w)) || w < narrowest || w <= rival_w)
            continue;
        recommend_desc e = *d;
        e.budget = recommend__gap_budget(p, s, k, j);
        e.check_budget = 0;
        recommend_result r;
        recommend_scene(p, n, &e, &r);
        if (r.pick != out->pick) {
            rival_w = w;
            out->budget_moves = 1;
            out->moved_budget = e.budget;
            out->moved_pick = r.pick;
        }
    }
    free(s);
}

void recommend_scene(const recommend_point *p, size_t n, const recommend_desc *desc,
                     recommend_result *out)
{
    recommend_desc d = desc ? *desc : (recommend_desc){0};
    size_t *scratch = dm_xcalloc(n + 1, sizeof *scratch);
    unsigned mask = recommend__eligible_mask(p, n, &out->lit_only);
    out->budget_default = !(d.budget > 0);
    out->budget = out->budget_default ? recommend_default_budget(p, n) : d.budget;
    out->pick = recommend__best_within(p, n, mask, d.epsilon, out->budget, scratch);
    out->pick_tie = RECOMMEND_NONE;
    out->pick_ci_over = 0;
    if (out->pick != RECOMMEND_NONE) {
        out->pick_tie = recommend__tie_of(p, n, mask, d.epsilon, d.resolvable, out->budget, out->pick);
        if (out->pick_tie != RECOMMEND_NONE && recommend__named_first(p, out->pick_tie, out->pick)) {
            /* the data cannot tell them apart: name the one a rule that
             * noise does not move puts first, not the lower median */
            size_t t = out->pick;
            out->pick = out->pick_tie;
            out->pick_tie = t;
        }
        out->pick_ci_over = p[out->pick].ci_hi > out->budget;
    }
    out->near_miss = recommend__near_miss_of(p, n, mask, d.epsilon, out->budget, out->pick);
    size_t m = recommend__front_of(p, n, mask, d.epsilon, scratch);
    out->fastest = m ? scratch[0] : RECOMMEND_NONE;
    out->knee = recommend__knee_of(p, scratch, m);
    for (int f = 0; f < RECOMMEND_FAMILY_COUNT; f++) {
        unsigned one = 1u << f;
        size_t k = recommend__sorted(p, n, one, scratch);
        out->family_fastest[f] = k ? scratch[0] : RECOMMEND_NONE;
        out->family_best[f] = recommend__best_within(p, n, one, d.epsilon, out->budget, scratch);
    }
    free(scratch);
    out->budget_moves = 0;
    out->moved_budget = NAN;
    out->moved_pick = RECOMMEND_NONE;
    if (out->budget_default && d.check_budget && out->budget > 0)
        recommend__budget_check(p, n, &d, out);
}

const char *recommend_family_name(recommend_family f)
{
    static const char *const names[RECOMMEND_FAMILY_COUNT] = {
        [RECOMMEND_UNLIT] = "unlit", [RECOMMEND_FRAGMENT] = "fragment",
        [RECOMMEND_VERTEX] = "vertex", [RECOMMEND_TESSELLATION] = "tessellation"};
    return (unsigned)f < RECOMMEND_FAMILY_COUNT ? names[f] : "?";
}
