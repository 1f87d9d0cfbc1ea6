/* answer.h — the recommendation of each scene of a run, in words.
 *
 * Builds reports/recommend.h points from a run (median WallTime with its CI,
 * the run's error metric, the family from the axes the technique reads:
 * tess_level → tessellation, vertex_filter → vertex, no `lighting` axis →
 * unlit baseline, else fragment) and says the pick under the frame budget,
 * the knee and the best of each family, marking noisy and bimodal timings.
 *
 * A scene without a frame time (a counters-only sweep) has no budget and no
 * pick: its answer says why and shows its counters (report_counter_table).
 *
 * The budget is the run's environment entry REPORT_BUDGET_KEY (ms; the
 * runner copies the sweep's quality.budget_ms, `dmbench report --budget-ms`
 * overrides it); absent or 0: each scene's recommend_default_budget().
 */
#ifndef REPORTS_ANSWER_H
#define REPORTS_ANSWER_H

#include "core/dm_results.h"
#include "core/dm_util.h"
#include "reports/recommend.h"

#define REPORT_BUDGET_KEY "budget_ms"

typedef enum report_answer_format {
    REPORT_ANSWER_TEXT = 0,   /* plain, for the terminal */
    REPORT_ANSWER_HTML,
    REPORT_ANSWER_MD
} report_answer_format;

/* Records ms (> 0) as the run's budget, replacing any; DM_ERR_ARG otherwise. */
int report_budget_set(dm_run_result *run, double ms);
/* The run's budget in ms; 0 when none is recorded (per-scene default). */
double report_budget_ms(const dm_run_result *run);

/* The family of a configuration (see above). */
recommend_family report_family(const dm_config_result *c);

/* One scene's recommendation: *out gets config indexes into run (NONE where
 * none).  Returns the number of points considered. */
size_t report_recommend(const dm_run_result *run, const char *scene, recommend_result *out);

/* The run's smallest resolvable relative difference between two
 * configurations (dm_run_noise_floor; NaN without WallTime): the
 * recommendation's ties use it (recommend_desc.resolvable). */
double report_resolvable(const dm_run_result *run);
/* The recommendation on the figures with the machine's drift removed
 * (corrected where the scene was corrected): 1 and *out as
 * report_recommend's, or 0 (out untouched) when no configuration of the
 * scene has corrected figures. */
int report_recommend_corrected(const dm_run_result *run, const char *scene, recommend_result *out);
/* Where the raw and the corrected figures disagree on the scene's verdict
 * (the pick, or whether it ties and with what), one sentence appended to
 * out (plain text) and 1; 0 and nothing when they agree or the scene was
 * not corrected.  The answer names the raw pick and adds this sentence. */
int report_answer_disagree(const dm_run_result *run, const char *scene, dm_str *out);

/* The scene's answer as sentences: the pick (or that nothing fits), the
 * tie and budget notes, the knee, the family bests and the unlit baseline
 * note.  HTML: a <p class="pick"> and a <ul>; MD: a paragraph and a list;
 * TEXT: a paragraph and indented lines. */
void report_answer_scene(const dm_run_result *run, const char *scene, report_answer_format f,
                         dm_str *out);

/* Why the scene has no budget and no pick, as a sentence ending ": no budget
 * or pick" ("no timing counter measured: …" for a counters-only run); NULL
 * when one of its ok configurations has a frame time. */
const char *report_untimed_reason(const dm_run_result *run, const char *scene);
/* 1 when some scene of the run has a frame time (a budget and a pick). */
int report_run_timed(const dm_run_result *run);

/* Terminal tables are cut into blocks of at most this many columns. */
#define REPORT_TERMINAL_WIDTH 100
/* The scene's counters (deterministic ones: counts, instructions, ratios),
 * a row per ok configuration labelled as in the scene's table, counts in
 * grouped digits: an HTML table, a Markdown table or indented text that
 * fits REPORT_TERMINAL_WIDTH.  Nothing when the scene has no such counter. */
void report_counter_table(const dm_run_result *run, const char *scene, report_answer_format f,
                          dm_str *out);

/* Every scene's TEXT answer, for the end of `dmbench run`; a scene without
 * a frame time says why and shows its counters instead. */
void report_answer_terminal(const dm_run_result *run, dm_str *out);

#endif
