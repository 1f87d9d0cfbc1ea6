/* tech_spec.h — test helper: configurations written "k=v k=v ..." and
 * prepared on a renderer.  Shared by the GL fixture (tech_fixture.h) and the
 * texture tests, which set up their own context. */
#ifndef TESTS_TECH_SPEC_H
#define TESTS_TECH_SPEC_H

#include <stddef.h>
#include "core/dm_results.h"
#include "core/dm_util.h"
#include "techniques/render.h"

#define TECHFIX_MAX_PARAMS 24
/* "k=v k=v ..." (at most TECHFIX_MAX_PARAMS pairs) into kv, using buf as storage. */
size_t parse(const char *spec, dm_kv kv[TECHFIX_MAX_PARAMS], char *buf, size_t cap);
/* Prepares spec on r and asserts render_prepare returned want (0 or a
 * DM_ERR_*); the driver's log goes to log (may be NULL) and to stderr when
 * the code differs. */
render_item spec_prepare(render_ctx *r, const char *spec, int want, dm_str *log);

#endif
