/* probe.c — user techniques compiled, and drivers asked, in a child with a
 * deadline (see probe.h). */
#include "run/probe.h"
#include "core/dm_error.h"
#include "core/dm_proc.h"
#include "run/drivers.h"
#include "run/gl_context.h"
#include "techniques/render.h"
#include "techniques/user_technique.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* The most a probe child may be given: a day. */
#define PROBE__MAX_S 86400.0

/* The value of PROBE_TIMEOUT_ENV in seconds, 0 when unset or empty, -1 when
 * it is not a number in (0, PROBE__MAX_S]. */
static double probe__env(void)
{
    const char *v = getenv(PROBE_TIMEOUT_ENV);
    if (!v || !*v)
        return 0;
    char *end = NULL;
    errno = 0;
    double s = strtod(v, &end);
    if (errno || end == v || *end || !isfinite(s) || s <= 0 || s > PROBE__MAX_S)
        return -1;
    return s;
}

int probe_env_check(dm_str *err)
{
    if (probe__env() >= 0)
        return 0;
    char *buf = NULL;
    dm_str_printf(err, "%s=%s: not a number of seconds in (0, %.0f]: how long a driver probe or a user "
                  "shader's compile may take before it is stopped (unset: %.0f)", PROBE_TIMEOUT_ENV,
                  dm_term_safe(getenv(PROBE_TIMEOUT_ENV), &buf), PROBE__MAX_S, PROBE_TIMEOUT_DEFAULT_S);
    free(buf);
    return DM_ERR_ARG;
}

double probe_timeout_s(void)
{
    double s = probe__env();
    return s > 0 ? s : PROBE_TIMEOUT_DEFAULT_S;
}

void probe_no_answer(const char *what, int timed_out, int status, double seconds, dm_str *err)
{
    if (timed_out)
        dm_str_printf(err, "%s did not answer within %g s (driver '%s' hung?); %s sets the limit", what,
                      probe_timeout_s(), drivers_current(), PROBE_TIMEOUT_ENV);
    else if (WIFSIGNALED(status))
        dm_str_printf(err, "%s crashed after %.1f s (signal %d, %s) on driver '%s'", what, seconds,
                      WTERMSIG(status), strsignal(WTERMSIG(status)), drivers_current());
    else
        dm_str_printf(err, "%s ended after %.1f s with exit status %d and no answer (driver '%s')", what,
                      seconds, WIFEXITED(status) ? WEXITSTATUS(status) : -1, drivers_current());
}

/* Writes one protocol line "TAG\tFIELDS\tTEXT" to fd, the text on one line. */
static void probe__line(int fd, const char *head, const char *text)
{
    char *t = dm_xstrdup(text ? text : "");
    for (char *c = t; *c; c++)
        *c = *c == '\n' ? '\x1f' : *c == '\t' ? ' ' : *c;
    dprintf(fd, "%s\t%s\n", head, t);
    free(t);
}

/* The child: a context, then each user technique compiled in turn, with
 * "K i" written before and "D i" after each (unbuffered, so a compile that
 * crashes or hangs is known by its "K"); "F" when there is no context, "U i
 * rc" with the message when technique i cannot be built. */
static void probe__user_child(int fd, void *arg)
{
    (void)arg;
    gl_context *gl = NULL;
    render_ctx *r = NULL;
    dm_str err = {0};
    if (gl_context_create(NULL, &gl, &err) != 0) {
        probe__line(fd, "F", dm_str_get(&err));
        return;
    }
    if (render_create(&r) != 0) {
        probe__line(fd, "F", "cannot set up the renderer in a fresh context");
        return;
    }
    for (size_t i = 0; i < user_technique_count(); i++) {
        dprintf(fd, "K\t%zu\n", i);
        dm_str_free(&err);
        int rc = user_technique_check_program(r, i, &err);
        if (rc != 0) {
            char head[64];
            snprintf(head, sizeof head, "U\t%zu\t%d", i, rc);
            probe__line(fd, head, dm_str_get(&err));
            break;
        }
        dprintf(fd, "D\t%zu\n", i);
    }
    dm_str_free(&err);
    render_destroy(r);
    gl_context_destroy(gl);
}

int probe_user_techniques(dm_str *err)
{
    size_t n = user_technique_count();
    if (n == 0)
        return 0;
    dm_proc_result res;
    dm_proc_collect(probe__user_child, NULL, probe_timeout_s(), &res);
    long pending = -1;   /* the technique being compiled when the output ended */
    size_t done = 0;
    int rc = 0;
    char *save = NULL;
    for (char *line = strtok_r(res.text, "\n", &save); line && rc == 0; line = strtok_r(NULL, "\n", &save)) {
        char *f = strchr(line, '\t');
        if (!f)
            continue;
        *f++ = '\0';
        if (strcmp(line, "K") == 0) {
            pending = strtol(f, NULL, 10);
        } else if (strcmp(line, "D") == 0) {
            pending = -1;
            done++;
        } else if (strcmp(line, "F") == 0) {
            dm_str_printf(err, "%s", f);
            rc = DM_ERR_GL;
        } else if (strcmp(line, "U") == 0) {
            char *msg = strchr(f, '\t'), *m2 = msg ? strchr(msg + 1, '\t') : NULL;
            rc = msg ? (int)strtol(msg + 1, NULL, 10) : DM_ERR_PARSE;
            for (char *c = m2 ? m2 + 1 : f; *c; c++)
                *c = *c == '\x1f' ? '\n' : *c;
            dm_str_cat(err, m2 ? m2 + 1 : f);
            rc = rc < 0 ? rc : DM_ERR_PARSE;
        }
    }
    const technique_desc *t = pending >= 0 && (size_t)pending < n ? user_technique_at((size_t)pending) : NULL;
    if (rc == 0 && done < n && t && res.timed_out) {
        dm_str_printf(err, "%s: compiling user technique '%s' took more than %g s, so it was stopped "
                      "(%s sets the limit): the driver cannot build this shader in reasonable time; "
                      "make it smaller or simpler", user_technique_path(t), t->name, probe_timeout_s(),
                      PROBE_TIMEOUT_ENV);
        rc = DM_ERR_PARSE;
    } else if (rc == 0 && done < n && t) {
        if (WIFSIGNALED(res.status))
            dm_str_printf(err, "%s: the GLSL compiler crashed on user technique '%s' (signal %d, %s): "
                          "the driver cannot build this shader; make it smaller or simpler (a very long "
                          "expression overflows the compiler's stack)", user_technique_path(t), t->name,
                          WTERMSIG(res.status), strsignal(WTERMSIG(res.status)));
        else
            dm_str_printf(err, "%s: the GLSL compiler ended the process (exit status %d) on user technique "
                          "'%s': the driver cannot build this shader; make it smaller or simpler",
                          user_technique_path(t), WIFEXITED(res.status) ? WEXITSTATUS(res.status) : -1, t->name);
        rc = DM_ERR_PARSE;
    } else if (rc == 0 && done < n) {
        if (!res.started)
            dm_str_printf(err, "cannot start the user-technique check: %s", strerror(res.status));
        else
            probe_no_answer("the user-technique check (a fresh GL context)", res.timed_out, res.status,
                            res.seconds, err);
        rc = DM_ERR_GL;
    }
    free(res.text);
    return rc;
}
