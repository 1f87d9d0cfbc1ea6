/* recommend.h — the answer per scene: which configuration to pick.
 *
 * Pure functions of points (median time with its 95 % CI, an error where
 * lower is better, a technique family); no run, no I/O, so the rules are
 * unit-tested on made-up fronts (tests/test_reports_recommend.c).
 *
 * The rules, as docs/reports.md states them to users:
 *  - Equal quality: two errors closer than epsilon are the same quality, and
 *    the cheaper (lower median) configuration wins.  The front is walked
 *    fastest first and keeps a point only when its error beats every kept
 *    point by more than epsilon, so duplicates collapse onto the cheapest.
 *  - Only lit techniques are recommended: unlit (baseline-only) points stay
 *    on the front and in the tables but are picked only when the scene has
 *    nothing else.
 *  - The budget pick is the best quality whose median fits the budget; when
 *    a configuration of equal quality has an overlapping time CI, or a
 *    median closer to the pick's than the run's smallest resolvable
 *    difference, the two cost the same as far as the data can tell, and
 *    the pick says so; of the two it names the simpler pipeline
 *    (fragment, vertex, tessellation), then the one first in the points'
 *    order: rules that noise does not move.
 *  - The knee is the front member farthest below the straight line from the
 *    fastest to the best member (log time, both axes scaled to [0, 1]);
 *    none with fewer than three members or a front without a bend.
 *  - Per family (fragment, vertex, tessellation) the best quality within the
 *    budget, by the same tie rule.
 *  - A near miss: the best-quality eligible point whose median is over the
 *    budget but whose CI reaches under it, when its error beats the pick's
 *    by more than epsilon (any such point when nothing fits): it may also
 *    fit, and the answer names it beside the pick.
 */
#ifndef REPORTS_RECOMMEND_H
#define REPORTS_RECOMMEND_H

#include <stddef.h>

/* Index meaning "none". */
#define RECOMMEND_NONE ((size_t)-1)

/* Where a technique does its surface detail; RECOMMEND_UNLIT (0) is the
 * baseline that reads no lighting. */
typedef enum recommend_family {
    RECOMMEND_UNLIT = 0,
    RECOMMEND_FRAGMENT,
    RECOMMEND_VERTEX,
    RECOMMEND_TESSELLATION,
    RECOMMEND_FAMILY_COUNT
} recommend_family;

typedef struct recommend_point {
    double time;           /* median frame time, ns */
    double ci_lo, ci_hi;   /* 95 % CI of the median, ns; NaN when unknown */
    double error;          /* lower is better; non-finite points are ignored */
    recommend_family family;
} recommend_point;

typedef struct recommend_desc {
    double budget;         /* frame budget, ns; 0 = recommend_default_budget() */
    double epsilon;        /* errors closer than this are equal; 0 = exact */
    double resolvable;     /* relative: two medians that differ by no more than this fraction of
                              the pick's also cost the same (the run's smallest resolvable
                              difference, docs/measurement.md); 0 = by CI overlap only */
    int check_budget;      /* with the default budget: whether it could sit in another gap of the
                              times with each time anywhere in its CI, so far that the pick changes
                              (recommend_result.budget_moves); 0 = not checked */
} recommend_desc;

typedef struct recommend_result {
    double budget;                 /* the budget used, ns */
    int budget_default;            /* 1 when desc->budget was 0 */
    int lit_only;                  /* 1 when unlit points were passed over */
    size_t pick;                   /* best quality within the budget; NONE: nothing fits.  When it
                                      ties (pick_tie), the one of the two with the simpler pipeline
                                      (family: fragment, vertex, tessellation), then the one first in
                                      the points' order, so that two runs whose medians trade places
                                      within their CIs name the same pick */
    size_t pick_tie;               /* the other of a tie: equal quality, and an overlapping time CI
                                      or a median within desc->resolvable of the best one's; NONE */
    int pick_ci_over;              /* 1 when the pick's CI reaches past the budget */
    size_t near_miss;              /* clearly better quality than the pick, median over the budget,
                                      CI reaching under it ("may also fit"); NONE */
    size_t fastest;                /* the fastest eligible point (shown when nothing fits) */
    size_t knee;                   /* NONE when the front has no bend */
    size_t family_best[RECOMMEND_FAMILY_COUNT];   /* within the budget; NONE */
    size_t family_fastest[RECOMMEND_FAMILY_COUNT];/* NONE when the family is absent */
    /* desc->check_budget: 1 when, with the times anywhere in their CIs, the
     * default budget could be moved_budget (ns) and the pick there would be
     * moved_pick (NONE: nothing fits); of several, the widest gap.  0, NaN
     * and NONE when not checked or when no such budget changes the pick */
    int budget_moves;
    double moved_budget;
    size_t moved_pick;
} recommend_result;

/* The epsilon-collapsed front of all n points (unlit included): indices into
 * front (capacity n) fastest first, each better than all before it by more
 * than epsilon.  Returns how many. */
size_t recommend_front(const recommend_point *p, size_t n, double epsilon, size_t *front);

/* The noise the default budget is built to stand still under: a factor
 * 1.1 (±10 %) on any median. */
#define RECOMMEND_NOISE 1.1
/* The default budget: it splits the scene's eligible times (the lit
 * points, or all when none is lit) at their widest gap.  Sorted fastest
 * first, the gap between two consecutive times that is widest on a log
 * scale and wider than 2 log RECOMMEND_NOISE; equal widths go to the gap
 * whose count of times under it is nearest half, then to the lower.  The
 * budget is the roundest value in the middle half of that gap (log scale):
 * a 1, 2 or 5 × 10^k ns first, then one significant digit, then two,
 * nearest the gap's geometric middle.  When no gap is that wide (or there
 * is one time), the budget admits every point: the round value at or above
 * the slowest × RECOMMEND_NOISE.
 * Why it holds still: which times fit depends only on the times' ratios,
 * so the host running every configuration faster or slower by one factor
 * between two runs (±8-11 % on a quiet VM, docs/measurement.md) moves no
 * time across the budget: the budget's value moves with the times, the
 * pick does not.  A change of each median by its own factor within
 * 1/RECOMMEND_NOISE .. RECOMMEND_NOISE moves each gap's width by at most
 * 2 log RECOMMEND_NOISE, so the gap is unchanged whenever it is wider than
 * every other by more than twice that; recommend_desc.check_budget says
 * where the times' own CIs allow another gap.
 * 0 when there is no finite positive time. */
double recommend_default_budget(const recommend_point *p, size_t n);

/* Fills *out for the n points.  desc may be NULL (defaults).  Never fails:
 * with no usable point every index is RECOMMEND_NONE. */
void recommend_scene(const recommend_point *p, size_t n, const recommend_desc *desc,
                     recommend_result *out);

/* "fragment", "vertex", "tessellation" or "unlit". */
const char *recommend_family_name(recommend_family f);

#endif
