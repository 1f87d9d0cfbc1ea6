/* recommend_run.h — a run's configurations as reports/recommend.h points,
 * and what the report model (report_model.c) derives from them once: the
 * frame budget, each configuration's family, each scene's recommendation,
 * and why a scene without a frame time has none.
 *
 * A point is an ok configuration with a frame time: its median WallTime
 * with its CI, its error under the run's metric, its family from the axes
 * its technique reads (tess_level → tessellation, vertex_filter → vertex,
 * no `lighting` axis → unlit baseline, else fragment).
 *
 * The budget is the run's environment entry REPORT_BUDGET_KEY (ms; the
 * runner copies the sweep's quality.budget_ms, `dmbench report --budget-ms`
 * overrides it); absent or 0: each scene's recommend_default_budget().
 */
#ifndef REPORTS_RECOMMEND_RUN_H
#define REPORTS_RECOMMEND_RUN_H

#include "core/dm_results.h"
#include "core/dm_util.h"
#include "reports/recommend.h"

#define REPORT_BUDGET_KEY "budget_ms"

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

/* Why the scene has no budget and no pick, as a sentence ending ": no budget
 * or pick" ("no timing counter measured: …" for a counters-only run); NULL
 * when one of its ok configurations has a frame time. */
const char *report_untimed_reason(const dm_run_result *run, const char *scene);

#endif
