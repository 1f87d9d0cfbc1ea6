/* dm_exit.h — the process exit codes of dmbench, and the one mapping from
 * DM_ERR_* codes to them.
 *
 * Every command returns one of these; the README's table and `dmbench help`
 * are printed from the same DM_EXITS list.  DM_EXIT_ENV is for failures of
 * the machine rather than of the input (disk full, a damaged results store):
 * a retry elsewhere may succeed, so scripts can tell it from bad input.
 */
#ifndef CORE_DM_EXIT_H
#define CORE_DM_EXIT_H

#define DM_EXITS(X)                                                               \
    X(OK,           0, "success")                                                 \
    X(FAILED,       1, "a check failed or a regression was found")                \
    X(USAGE,        2, "bad input or usage (the message names file, line and the valid choices)") \
    X(INCONCLUSIVE, 3, "inconclusive (compare: too noisy to decide)")             \
    X(ENV,          4, "environment failure (disk full, damaged results store)")

typedef enum dm_exit {
#define DM__EXIT_ENUM(name, code, meaning) DM_EXIT_##name = (code),
    DM_EXITS(DM__EXIT_ENUM)
#undef DM__EXIT_ENUM
} dm_exit;

/* The exit code for a DM_ERR_* code: 0 → DM_EXIT_OK; input the user can fix
 * (ARG, PARSE, RANGE, UNKNOWN, NOTFOUND, EXISTS, IO, UNSUPPORTED) →
 * DM_EXIT_USAGE; the machine rather than the input (STORE: a damaged,
 * locked or full store; BUSY: the output in use by another run; CHILD:
 * measuring processes that keep dying; GL: no usable context; DISK: a
 * write the disk refused; NOMEM: an allocation the machine refused) →
 * DM_EXIT_ENV; everything else (a shader, numeric or timeout failure) →
 * DM_EXIT_FAILED.  docs/reliability.md lists which failure gets which code. */
dm_exit dm_exit_from_error(int err);
/* One-line meaning of an exit code, or NULL for a code not in DM_EXITS. */
const char *dm_exit_meaning(int code);

#endif
