/* trends.h — the report's trend lines from the store: per configuration of
 * a run, its median WallTime in every run of the store on the same machine
 * fingerprint up to and including this one (store/store_history.h). */
#ifndef RUN_TRENDS_H
#define RUN_TRENDS_H

#include "core/dm_results.h"
#include "reports/report.h"
#include "store/store.h"

/* Fills *out (zeroed first; release with report_trends_free) with one entry
 * per ok configuration of run found in the store.  0, or DM_ERR_STORE
 * (then *out is empty: the report goes on without trend lines). */
int run_trends(store *st, const dm_run_result *run, report_trends *out);

#endif
