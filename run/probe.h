/* probe.h — what is tried in a child with a deadline before a command does
 * GL work in its own process (docs/reliability.md, "Interruptions").
 *
 * A driver that hangs at start-up (zink without a Vulkan device) or a user
 * GLSL file that crashes the driver's compiler or keeps it busy for minutes
 * would otherwise hang or kill the command itself.  So `run`'s driver probe,
 * `info`, and the user-technique check of `run`, `render` and `predict`
 * happen in a child process (core/dm_proc.h) that is stopped after
 * probe_timeout_s() seconds without an answer, and what went wrong is said
 * with the right exit code: the user's file (2) or the machine (4).
 */
#ifndef RUN_PROBE_H
#define RUN_PROBE_H

#include "core/dm_util.h"

/* Seconds a probe child may stay silent: this variable, else 120. */
#define PROBE_TIMEOUT_ENV "DMBENCH_PROBE_TIMEOUT"
#define PROBE_TIMEOUT_DEFAULT_S 120.0

/* Checks PROBE_TIMEOUT_ENV when it is set: 0, or DM_ERR_ARG with
 * "DMBENCH_PROBE_TIMEOUT=VALUE: ..." and what is accepted in err. */
int probe_env_check(dm_str *err);
/* The deadline of a probe child in seconds (PROBE_TIMEOUT_ENV when valid,
 * else PROBE_TIMEOUT_DEFAULT_S). */
double probe_timeout_s(void);
/* "the driver did not answer within N s (...)" for a probe child that was
 * stopped at the deadline or died, appended to err; what is the subject of
 * the sentence, e.g. "the driver probe". */
void probe_no_answer(const char *what, int timed_out, int status, double seconds, dm_str *err);

/* Compiles every loaded user technique (techniques/user_technique.h) in a
 * child process with its own GL context, one at a time, each given
 * probe_timeout_s().  Returns 0 when each compiles and links (or none is
 * loaded); DM_ERR_PARSE naming the file when one does not compile, crashes
 * the GLSL compiler or compiles for longer than the deadline (the user's
 * file: exit 2); DM_ERR_GL when no context can be made or the child dies
 * before it compiles anything (the machine's: exit 4).  Message in err. */
int probe_user_techniques(dm_str *err);

#endif
