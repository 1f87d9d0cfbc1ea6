/* test_reports_recommend.c — the pick per scene on made-up fronts whose
 * answers are worked out by hand in the comments. */
#include "reports/recommend.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>
#include "test_util.h"

#define MS 1e6
#define F RECOMMEND_FRAGMENT
#define V RECOMMEND_VERTEX
#define T RECOMMEND_TESSELLATION
#define U RECOMMEND_UNLIT

/* A point at t ms ± r (fraction of t) with error e. */
static recommend_point pt(double t, double r, double e, recommend_family f)
{
    return (recommend_point){t * MS, t * MS * (1 - r), t * MS * (1 + r), e, f};
}

/* Epsilon 0 is the plain Pareto front (x = ms, error):
 *   0 (1, 9) fastest · 1 (2, 5) · 2 (3, 6) dominated by 1 · 3 (4, 2)
 *   4 (5, 2) equal error, slower than 3 · 5 (6, 1) most accurate
 *   6 (7, 8) dominated · 7 (NaN, 0) ignored, must not knock out 5
 *   8 (2, 5) equal to 1: one of equals stays, the lower index */
static void test_front_known_points(void **state)
{
    (void)state;
    double x[] = {1, 2, 3, 4, 5, 6, 7, NAN, 2}, y[] = {9, 5, 6, 2, 2, 1, 8, 0, 5};
    recommend_point p[9];
    for (int i = 0; i < 9; i++)
        p[i] = (recommend_point){x[i], NAN, NAN, y[i], F};
    size_t out[9], expect[] = {0, 1, 3, 5};
    assert_int_equal(recommend_front(p, 9, 0, out), 4);
    for (size_t i = 0; i < 4; i++)
        assert_int_equal(out[i], expect[i]);
    assert_int_equal(recommend_front(p, 0, 0, out), 0);
    /* listed slowest first, a trade-off comes out fastest first */
    recommend_point q[] = {{9, NAN, NAN, 1, F}, {5, NAN, NAN, 5, F}, {1, NAN, NAN, 9, F}};
    assert_int_equal(recommend_front(q, 3, 0, out), 3);
    assert_int_equal(out[0], 2);
    assert_int_equal(out[2], 0);
}

/* Equal quality within epsilon collapses onto the cheaper point: the
 * issue's tess_level=1 (0.126703) and vertex-displacement (0.126700) case. */
static void test_equal_quality_cheaper_wins(void **state)
{
    (void)state;
    recommend_point p[] = {
        pt(2.0, 0.02, 0.20, F),      /* 0: fastest */
        pt(6.0, 0.02, 0.126703, T),  /* 1: tess_level=1 */
        pt(5.0, 0.02, 0.126700, V),  /* 2: vertex-displacement, cheaper, 3e-6 better */
        pt(9.0, 0.02, 0.05, F),      /* 3: clearly better */
    };
    size_t front[4];
    /* exact (epsilon 0): 2 beats 1 by 3e-6 and is cheaper, 1 is dominated anyway */
    assert_int_equal(recommend_front(p, 4, 0, front), 3);
    /* swap so the worse-by-3e-6 one is cheaper: exact keeps both, epsilon one */
    p[1].error = 0.126700, p[2].error = 0.126703;
    assert_int_equal(recommend_front(p, 4, 0, front), 4);
    assert_int_equal(front[0], 0);
    assert_int_equal(front[1], 2);
    assert_int_equal(front[2], 1);
    assert_int_equal(recommend_front(p, 4, 1e-3, front), 3);
    assert_int_equal(front[0], 0);
    assert_int_equal(front[1], 2);   /* the cheaper of the two equal ones */
    assert_int_equal(front[2], 3);
    /* the budget pick among them is the cheaper too */
    recommend_desc d = {.budget = 7 * MS, .epsilon = 1e-3};
    recommend_result r;
    recommend_scene(p, 4, &d, &r);
    assert_int_equal(r.pick, 2);
    /* their CIs (4.9–5.1 and 5.88–6.12) do not overlap: no tie to report */
    assert_int_equal(r.pick_tie, RECOMMEND_NONE);
    /* widen the costlier one's CI to reach 5.05: same cost as far as the data tells */
    p[1].ci_lo = 5.05 * MS;
    recommend_scene(p, 4, &d, &r);
    assert_int_equal(r.pick, 2);
    assert_int_equal(r.pick_tie, 1);
    /* the medians trade places within their CIs (another run's noise): the same pick,
     * the simpler pipeline (vertex before tessellation), not the lower median */
    recommend_point q[4];
    memcpy(q, p, sizeof q);
    q[1].time = 5.0 * MS, q[1].ci_lo = 4.9 * MS, q[1].ci_hi = 5.1 * MS;
    q[2].time = 5.2 * MS, q[2].ci_lo = 5.05 * MS, q[2].ci_hi = 5.35 * MS;
    recommend_scene(q, 4, &d, &r);
    assert_int_equal(r.pick, 2);
    assert_int_equal(r.pick_tie, 1);
    /* of one family, the one first in the points' order, whichever median is lower */
    q[1].family = q[2].family = F;
    recommend_scene(q, 4, &d, &r);
    assert_int_equal(r.pick, 1);
    assert_int_equal(r.pick_tie, 2);
    q[1].time = 5.3 * MS, q[2].time = 5.0 * MS;
    recommend_scene(q, 4, &d, &r);
    assert_int_equal(r.pick, 1);
    assert_int_equal(r.pick_tie, 2);
}

/* The run's smallest resolvable difference makes a tie of two equal-quality
 * medians closer than it, even when their CIs do not overlap. */
static void test_tie_within_resolvable_difference(void **state)
{
    (void)state;
    recommend_point p[] = {
        pt(2.0, 0.02, 0.20, F),      /* 0: fastest */
        pt(5.3, 0.01, 0.1267, T),    /* 1: 5.247–5.353 ms, 6 % above 2's median */
        pt(5.0, 0.01, 0.1267, V),    /* 2: 4.95–5.05 ms: the pick */
    };
    recommend_result r;
    recommend_desc d = {.budget = 7 * MS, .epsilon = 1e-3};
    recommend_scene(p, 3, &d, &r);   /* CIs apart, no resolvable difference: no tie */
    assert_int_equal(r.pick, 2);
    assert_int_equal(r.pick_tie, RECOMMEND_NONE);
    d.resolvable = 0.05;             /* 0.3 ms > 5 % of 5 ms: still told apart */
    recommend_scene(p, 3, &d, &r);
    assert_int_equal(r.pick_tie, RECOMMEND_NONE);
    d.resolvable = 0.07;             /* 0.3 ms < 7 % of 5 ms: the run cannot tell them apart */
    recommend_scene(p, 3, &d, &r);
    assert_int_equal(r.pick, 2);
    assert_int_equal(r.pick_tie, 1);
    d.resolvable = 0.5;              /* quality decides the rest: 0 is not equal quality */
    recommend_scene(p, 3, &d, &r);
    assert_int_equal(r.pick_tie, 1);
}

/* The budget is respected: the pick's median is within it, and it is the
 * best quality that is. */
static void test_budget_respected(void **state)
{
    (void)state;
    recommend_point p[] = {
        pt(1.0, 0.01, 0.30, F), pt(3.0, 0.01, 0.20, F), pt(8.0, 0.01, 0.10, V),
        pt(20.0, 0.01, 0.05, T), pt(50.0, 0.01, 0.04, T),
    };
    recommend_desc d = {.budget = 10 * MS, .epsilon = 1e-3};
    recommend_result r;
    recommend_scene(p, 5, &d, &r);
    assert_int_equal(r.budget_default, 0);
    assert_int_equal(r.pick, 2);
    assert_int_equal(r.pick_ci_over, 0);
    d.budget = 8.05 * MS;   /* 8 ms fits, its CI (7.92–8.08) reaches past */
    recommend_scene(p, 5, &d, &r);
    assert_int_equal(r.pick, 2);
    assert_int_equal(r.pick_ci_over, 1);
    d.budget = 7.99 * MS;
    recommend_scene(p, 5, &d, &r);
    assert_int_equal(r.pick, 1);
    d.budget = 0.5 * MS;    /* nothing fits: no pick, the fastest is named */
    recommend_scene(p, 5, &d, &r);
    assert_int_equal(r.pick, RECOMMEND_NONE);
    assert_int_equal(r.fastest, 0);
    d.budget = 1000 * MS;   /* everything fits: the best */
    recommend_scene(p, 5, &d, &r);
    assert_int_equal(r.pick, 4);
    assert_int_equal(r.near_miss, RECOMMEND_NONE);
}

/* A near miss: median over the budget, CI under it, clearly better than
 * the pick; not when only as good, not when its CI stays above. */
static void test_near_miss(void **state)
{
    (void)state;
    recommend_point p[] = {
        pt(4.06, 0.01, 0.127, F),   /* the pick under 5 ms */
        pt(5.03, 0.03, 0.102, F),   /* CI 4.88..5.18: reaches under 5 ms, clearly better */
        pt(5.50, 0.05, 0.050, T),   /* CI 5.23..5.78: stays above */
    };
    recommend_desc d = {.budget = 5 * MS, .epsilon = 1e-3};
    recommend_result r;
    recommend_scene(p, 3, &d, &r);
    assert_int_equal(r.pick, 0);
    assert_int_equal(r.near_miss, 1);
    p[1].error = 0.1268;            /* as good as the pick within epsilon: no near miss */
    recommend_scene(p, 3, &d, &r);
    assert_int_equal(r.near_miss, RECOMMEND_NONE);
    d.budget = 4.0 * MS;            /* nothing fits: the one whose CI reaches under it may fit */
    p[0].ci_lo = 3.98 * MS;
    recommend_scene(p, 3, &d, &r);
    assert_int_equal(r.pick, RECOMMEND_NONE);
    assert_int_equal(r.near_miss, 0);
}

/* Family bests within the budget, absent families NONE. */
static void test_family_bests(void **state)
{
    (void)state;
    recommend_point p[] = {
        pt(1.0, 0.01, 0.50, U),   /* 0: unlit baseline, fastest */
        pt(2.0, 0.01, 0.30, F),   /* 1 */
        pt(4.0, 0.01, 0.12, F),   /* 2: best fragment within 10 ms */
        pt(12.0, 0.01, 0.06, F),  /* 3: better, over budget */
        pt(6.0, 0.01, 0.15, V),   /* 4: best vertex */
        pt(9.0, 0.01, 0.1500004, V), /* 5: equal to 4 within epsilon, costlier */
        pt(15.0, 0.01, 0.02, T),  /* 6: the only tessellation, over budget */
    };
    recommend_desc d = {.budget = 10 * MS, .epsilon = 1e-3};
    recommend_result r;
    recommend_scene(p, 7, &d, &r);
    assert_int_equal(r.family_best[F], 2);
    assert_int_equal(r.family_best[V], 4);
    assert_int_equal(r.family_best[T], RECOMMEND_NONE);
    assert_int_equal(r.family_fastest[T], 6);
    assert_int_equal(r.family_best[U], 0);
    assert_int_equal(r.pick, 2);
    assert_int_equal(r.lit_only, 1);
    assert_int_equal(r.fastest, 1);   /* the unlit one is not eligible */
}

/* Unlit points are picked only when nothing else exists. */
static void test_unlit_only_when_alone(void **state)
{
    (void)state;
    recommend_point p[] = {pt(1.0, 0.01, 0.01, U), pt(3.0, 0.01, 0.20, F)};
    recommend_desc d = {.budget = 10 * MS, .epsilon = 1e-3};
    recommend_result r;
    recommend_scene(p, 2, &d, &r);
    assert_int_equal(r.pick, 1);   /* worse and slower, but lit */
    size_t front[2];
    assert_int_equal(recommend_front(p, 2, 1e-3, front), 1);   /* the front keeps the unlit one */
    assert_int_equal(front[0], 0);
    p[1].error = NAN;              /* the lit one has no quality: unlit it is */
    recommend_scene(p, 2, &d, &r);
    assert_int_equal(r.pick, 0);
    assert_int_equal(r.lit_only, 0);
}

/* The knee: log time and error scaled to [0, 1]; the line runs from
 * (0, 1) to (1, 0).  Times 1, 10, 100 ms give x = 0, 0.5, 1; the errors
 * 1.0, 0.2, 0.0 give the middle y = 0.2, so it lies 1 − 0.5 − 0.2 = 0.3
 * below the line: the knee.  With 0.6 instead it lies above: no knee. */
static void test_knee(void **state)
{
    (void)state;
    recommend_point p[] = {pt(1, 0.01, 1.0, F), pt(10, 0.01, 0.2, F), pt(100, 0.01, 0.0, F),
                           pt(50, 0.01, 0.5, F)};   /* dominated by 1 */
    recommend_result r;
    recommend_scene(p, 4, NULL, &r);
    assert_int_equal(r.knee, 1);
    p[1].error = 0.6;   /* y = 0.6, 1 − 0.5 − 0.6 < 0: above the line */
    recommend_scene(p, 4, NULL, &r);
    assert_int_equal(r.knee, RECOMMEND_NONE);
    recommend_scene(p, 2, NULL, &r);   /* two members: no knee */
    assert_int_equal(r.knee, RECOMMEND_NONE);
}

/* The default budget: the roundest value in the middle half of the widest
 * gap (log scale) between consecutive eligible times. */
static void test_default_budget(void **state)
{
    (void)state;
    /* 2.3 and 206 ms (the unlit 0.1 ms point is not counted): one gap, its
     * middle half 2.3 × (206 / 2.3)^(1/4) = 7.07 to 67.1 ms; of 10, 20 and
     * 50 ms, 20 is nearest √(2.3 × 206) = 21.8 */
    recommend_point p[] = {pt(2.3, 0.01, 0.2, F), pt(206, 0.01, 0.1, T), pt(0.1, 0.01, 0.5, U)};
    assert_true(fabs(recommend_default_budget(p, 3) - 20 * MS) < 1);
    recommend_result r;
    recommend_scene(p, 3, NULL, &r);
    assert_int_equal(r.budget_default, 1);
    assert_int_equal(r.pick, 0);
    /* one point at 2.3 ms: no gap, so all are admitted: the round value at
     * or above 2.3 × 1.1 = 2.53 ms is 5 ms */
    assert_true(fabs(recommend_default_budget(p, 1) - 5 * MS) < 1);
    /* 30 and 80 ms: middle half 38.3-62.6 ms, 50 ms */
    recommend_point q[] = {pt(30, 0.01, 0.2, F), pt(80, 0.01, 0.1, F)};
    assert_true(fabs(recommend_default_budget(q, 2) - 50 * MS) < 1);
    assert_true(recommend_default_budget(q, 0) == 0);
    /* the widest gap is 1.05 → 1.9 ms (a factor 1.81); its middle half,
     * 1.218-1.638 ms, holds no 1-2-5 value and no one-digit value: of the
     * two-digit ones 1.4 ms is nearest √(1.05 × 1.9) = 1.412 */
    recommend_point a[] = {pt(0.45, 0.01, 0.6, F), pt(0.54, 0.01, 0.5, F), pt(0.95, 0.01, 0.4, F),
                           pt(1.05, 0.01, 0.3, F), pt(1.9, 0.01, 0.2, F), pt(2.1, 0.01, 0.1, F)};
    assert_true(fabs(recommend_default_budget(a, 6) - 1.4 * MS) < 1);
    /* no gap wider than a factor 1.1² = 1.21: all admitted, the round value
     * at or above 1.3 × 1.1 = 1.43 ms is 2 ms */
    recommend_point c[] = {pt(1.0, 0.01, 0.4, F), pt(1.1, 0.01, 0.3, F), pt(1.2, 0.01, 0.2, F),
                           pt(1.3, 0.01, 0.1, F)};
    assert_true(fabs(recommend_default_budget(c, 4) - 2 * MS) < 1);
    /* equal gaps (each a factor 4): 2.5, 10, 40 ms; the gaps after 2.5 and
     * after 10 have 1 and 2 times under them, both 0.5 from half of 3: the
     * lower, middle half 3.54-7.07 ms, 5 ms; with an 80 ms point half is 2
     * and the gap after 10 splits it exactly: 14.1-28.3 ms, 20 ms */
    recommend_point e[] = {pt(2.5, 0.01, 0.3, F), pt(10, 0.01, 0.2, F), pt(40, 0.01, 0.1, F),
                           pt(80, 0.01, 0.05, F)};
    assert_true(fabs(recommend_default_budget(e, 3) - 5 * MS) < 1);
    assert_true(fabs(recommend_default_budget(e, 4) - 20 * MS) < 1);
}

/* A fixed linear congruential stream in [0, 1), so the test is repeatable. */
static double next_unit(uint64_t *s)
{
    *s = *s * 6364136223846793005u + 1442695040888963407u;
    return (double)(*s >> 11) / 9007199254740992.0;
}

/* Which of the n lit times (ms) t, each times its factor f, the default
 * budget admits: bit i for t[i]. */
static unsigned admitted_scaled(const double *t, const double *f, size_t n)
{
    recommend_point p[16] = {{0}};   /* all read are set below; -O1 with ASan cannot see n <= 16 */
    for (size_t i = 0; i < n; i++)
        p[i] = pt(t[i] * f[i], 0.1, 0.1 * (double)i, F);
    double b = recommend_default_budget(p, n);
    unsigned in = 0;
    for (size_t i = 0; i < n; i++)
        in |= (unsigned)(p[i].time <= b) << i;
    return in;
}

/* Under every corner of ±10 % (each median ×0.9 or ×1.1), 2000 random
 * factors in [0.9, 1.1] and every common factor 0.5-2 (the host's speed
 * between runs), the budget of t admits the same times as unperturbed;
 * returns that set. */
static unsigned assert_budget_holds(const double *t, size_t n)
{
    double f[16] = {0}; /* all set below; -O1 with ASan cannot see n <= 16 */
    for (size_t i = 0; i < n; i++)
        f[i] = 1;
    unsigned want = admitted_scaled(t, f, n);
    for (unsigned corner = 0; corner < 1u << n; corner++) {
        for (size_t i = 0; i < n; i++)
            f[i] = corner >> i & 1 ? 1.1 : 0.9;
        assert_int_equal(admitted_scaled(t, f, n), want);
    }
    uint64_t seed = 46;
    for (int k = 0; k < 2000; k++) {
        for (size_t i = 0; i < n; i++)
            f[i] = 0.9 + 0.2 * next_unit(&seed);
        assert_int_equal(admitted_scaled(t, f, n), want);
        double common = pow(2, 2 * next_unit(&seed) - 1);
        for (size_t i = 0; i < n; i++)
            f[i] = common;
        assert_int_equal(admitted_scaled(t, f, n), want);
    }
    return want;
}

/* Issue 46, item 3: two identical --quick runs chose 0.5 ms, then 1 ms, for
 * one scene; issue 50: two quiet default runs, the second 10.3 % faster
 * throughout one scene, chose 5 ms, then 20 ms, and named two picks.  The
 * budget now splits the times at their widest gap, which the host's common
 * speed does not move. */
static void test_default_budget_holds_still(void **state)
{
    (void)state;
    /* The lit medians (ms) of `run --quick` on 2026-11-29 (llvmpipe, load
     * average 11.7 from other builds), plane 80×45: the widest gap is
     * 0.327 → 0.711 (a factor 2.17; the next is 1.14), 0.5 ms, and it
     * admits the six fastest */
    const double q80[] = {0.242, 0.327, 0.718, 0.237, 0.269, 0.711, 0.205, 0.326};
    assert_int_equal(assert_budget_holds(q80, 8), 0xdb);
    recommend_point p[8] = {{0}};
    for (size_t i = 0; i < 8; i++)
        p[i] = pt(q80[i], 0.1, 0.1 * (double)i, F);
    assert_true(fabs(recommend_default_budget(p, 8) - 0.5 * MS) < 1);
    /* plane 160×90: 1.130 → 2.647 (a factor 2.34), 2 ms, the six fastest */
    const double q160[] = {0.965, 1.130, 3.151, 0.781, 0.796, 2.647, 0.749, 1.064};
    assert_int_equal(assert_budget_holds(q160, 8), 0xdb);
    /* Issue 50's scene, cube 240×135 of the default sweep (29 Nov 2026
     * 15:53 UTC, llvmpipe, load 1.1): its lit medians, then the same
     * scene's in the next run, every one 5-11 % lower.  The widest gap,
     * 5.87 → 10.07 ms, then 5.38 → 9.03, is the same gap in both: 8 ms
     * (nearest √(5.87 × 10.07) = 7.69 of the one-digit values in its middle
     * half, 6.72-8.80 ms), then 7 ms (6.97; 6.12-7.93 ms), the eight
     * fastest in each */
    const double run3[] = {2.28, 2.89, 2.90, 2.92, 3.84, 4.12, 5.76, 5.87, 10.07, 10.19, 10.23};
    const double run4[] = {2.13, 2.73, 2.73, 2.84, 3.51, 3.64, 5.30, 5.38, 9.03, 9.17, 9.26};
    recommend_point a[11] = {{0}}, b[11] = {{0}};
    for (size_t i = 0; i < 11; i++)
        a[i] = pt(run3[i], 0.03, 0.1 * (double)(11 - i), F), b[i] = pt(run4[i], 0.03, 0.1 * (double)(11 - i), F);
    recommend_result ra, rb;
    recommend_desc d = {.epsilon = 1e-3, .check_budget = 1};
    recommend_scene(a, 11, &d, &ra);
    recommend_scene(b, 11, &d, &rb);
    assert_int_equal(ra.pick, 7);
    assert_int_equal(rb.pick, 7);
    assert_true(fabs(ra.budget - 8 * MS) < 1 && fabs(rb.budget - 7 * MS) < 1);
    assert_int_equal(ra.budget_moves, 0);   /* ±3 % CIs: 5.87 → 10.07 stays the widest */
    assert_int_equal(rb.budget_moves, 0);
}

/* Where the times' CIs allow the budget another gap and another pick, the
 * pick is said to move (the answer marks it provisional). */
static void test_default_budget_moves(void **state)
{
    (void)state;
    /* 0.36 → 0.9 (a factor 2.5) and 0.9 → 2.2 (2.44): nearly as wide; the
     * first wins, 0.5 ms, and admits 0.36 (the best of the five fastest) */
    const double t[] = {0.22, 0.25, 0.30, 0.33, 0.36, 0.9, 2.2, 2.3};
    recommend_point p[8] = {{0}};
    for (size_t i = 0; i < 8; i++)
        p[i] = pt(t[i], 0.001, 0.1 * (double)(8 - i), F);
    recommend_desc d = {.epsilon = 1e-3, .check_budget = 1};
    recommend_result r;
    recommend_scene(p, 8, &d, &r);
    assert_true(fabs(r.budget - 0.5 * MS) < 1);
    assert_int_equal(r.pick, 4);
    assert_int_equal(r.budget_moves, 0);   /* ±0.1 % CIs: 2.5 / 1.002² > 2.44 × 1.002² */
    for (size_t i = 0; i < 8; i++)         /* ±3 % CIs: 2.5 / 1.03² = 2.36 < 2.44 × 1.03² = 2.59 */
        p[i] = pt(t[i], 0.03, 0.1 * (double)(8 - i), F);
    recommend_scene(p, 8, &d, &r);
    assert_int_equal(r.pick, 4);
    assert_int_equal(r.budget_moves, 1);
    /* the rival gap 0.9 → 2.2: its middle half 1.13-1.76 ms, 1.4 ms (two
     * digits, nearest √(0.9 × 2.2) = 1.41), where 0.9 ms is the pick */
    assert_true(fabs(r.moved_budget - 1.4 * MS) < 1);
    assert_int_equal(r.moved_pick, 5);
    recommend_point q[8];                  /* CIs unknown (NaN) or nonsense (a low end of 0, past
                                              the median): the medians stand for them, no move */
    for (size_t i = 0; i < 8; i++) {
        q[i] = p[i];
        q[i].ci_lo = i % 2 ? NAN : 0;
        q[i].ci_hi = i % 2 ? NAN : q[i].time * 0.5;
    }
    recommend_scene(q, 8, &d, &r);
    assert_int_equal(r.pick, 4);
    assert_int_equal(r.budget_moves, 0);
    d.check_budget = 0;                    /* not asked: not checked */
    recommend_scene(p, 8, &d, &r);
    assert_int_equal(r.budget_moves, 0);
    assert_int_equal(r.moved_pick, RECOMMEND_NONE);
    d.budget = 0.5 * MS;                   /* a budget given is never checked */
    d.check_budget = 1;
    recommend_scene(p, 8, &d, &r);
    assert_int_equal(r.budget_moves, 0);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_front_known_points),
             cmocka_unit_test(test_equal_quality_cheaper_wins),
             cmocka_unit_test(test_tie_within_resolvable_difference),
             cmocka_unit_test(test_budget_respected),
             cmocka_unit_test(test_near_miss),
             cmocka_unit_test(test_family_bests),
             cmocka_unit_test(test_unlit_only_when_alone),
             cmocka_unit_test(test_knee),
             cmocka_unit_test(test_default_budget),
             cmocka_unit_test(test_default_budget_holds_still),
             cmocka_unit_test(test_default_budget_moves))
