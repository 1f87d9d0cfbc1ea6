/* answer.h — the recommendation of each scene of a run, in words.
 *
 * Written from the report model (report_model.h), which holds what the
 * sentences say: each scene's recommendation (recommend_run.h: the points,
 * the budget, the families), the labels, times with their CIs, the noise
 * marks and image defects of each configuration, and whether the pick is
 * provisional.  The pick under the frame budget, the knee and the best of
 * each family are said with their marks.
 *
 * A scene without a frame time (a counters-only sweep) has no budget and no
 * pick: its answer says why and shows its counters (report_counter_table).
 */
#ifndef REPORTS_ANSWER_H
#define REPORTS_ANSWER_H

#include "core/dm_results.h"
#include "core/dm_util.h"
#include "reports/recommend.h"
#include "reports/recommend_run.h"
#include "reports/report_model.h"

typedef enum report_answer_format {
    REPORT_ANSWER_TEXT = 0,   /* plain, for the terminal */
    REPORT_ANSWER_HTML,
    REPORT_ANSWER_MD
} report_answer_format;

/* Scene si's answer as sentences: the pick (or that nothing fits), the
 * tie and budget notes, the knee, the family bests and the unlit baseline
 * note.  HTML: a <p class="pick"> and a <ul>; MD: a paragraph and a list;
 * TEXT: a paragraph and indented lines. */
void report_answer_scene(const report_model *m, size_t si, report_answer_format f, dm_str *out);

/* Terminal tables are cut into blocks of at most this many columns. */
#define REPORT_TERMINAL_WIDTH 100
/* Scene si's counters (deterministic ones: counts, instructions, ratios),
 * a row per ok configuration labelled as in the scene's table, counts in
 * grouped digits: an HTML table, a Markdown table or indented text that
 * fits REPORT_TERMINAL_WIDTH.  Nothing when the scene has no such counter. */
void report_counter_table(const report_model *m, size_t si, report_answer_format f, dm_str *out);

/* Every scene's TEXT answer, for the end of `dmbench run`, each line
 * word-wrapped to 100 columns; a scene without a frame time says why and
 * shows its counters instead.  report_answer_terminal builds the run's
 * model (no directory, no trends) for it and frees it (report_write.c). */
void report_answer_terminal_model(const report_model *m, dm_str *out);
void report_answer_terminal(const dm_run_result *run, dm_str *out);

#endif
