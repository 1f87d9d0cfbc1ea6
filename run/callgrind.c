/* callgrind.c — the Instructions pass: launching the child under Valgrind,
 * its watchdog, and reading callgrind's dump files (see callgrind.h). */
#include "run/callgrind.h"
#include "core/dm_error.h"
#include "core/dm_proc.h"
#include "counters/counters.h"
#include "run/path_timing.h"
#include "techniques/user_technique.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

void callgrind_mark_unavailable(callgrind_count *out, const plan_config *cs, size_t n,
                                const char *why)
{
    for (size_t i = 0; i < n; i++) {
        snprintf(out[i].key, sizeof out[i].key, "%s", cs[i].key);
        out[i].reason = dm_xstrdup(why);
    }
}

void callgrind_counts_free(callgrind_count *c, size_t n)
{
    for (size_t i = 0; c && i < n; i++) {
        free(c[i].reason);
        free(c[i].stage_reason);
    }
}

int callgrind_is_stage_counter(const char *name)
{
    static const char *const stages[] = {"GeometryInstructions", "RasterInstructions", "FragmentInstructions",
                                         "StageResidual"};
    for (size_t i = 0; name && i < sizeof stages / sizeof stages[0]; i++)
        if (strcmp(name, stages[i]) == 0)
            return 1;
    return 0;
}

/* counters_derive_inputs check that notes a stage-counter input in *user. */
static int cg__stage_input(const char *input, void *user)
{
    if (callgrind_is_stage_counter(input))
        *(int *)user = 1;
    return 1;
}

int callgrind_wants_stages(const sweep_measure *sm)
{
    for (size_t i = 0; i < sm->n_counters; i++) {
        const counters_info *ci = counters_find(sm->counters[i]);
        int via = callgrind_is_stage_counter(sm->counters[i]);
        if (ci && ci->backend == COUNTERS_BACKEND_DERIVED)
            counters_derive_inputs(ci->name, cg__stage_input, &via);
        if (via)
            return 1;
    }
    return 0;
}

char *callgrind_disagreement(const callgrind_count *c)
{
    if (!c->counted)
        return NULL;
    double lo = c->samples[0], hi = c->samples[0];
    for (int s = 1; s < CALLGRIND_SAMPLES; s++) {
        lo = c->samples[s] < lo ? c->samples[s] : lo;
        hi = c->samples[s] > hi ? c->samples[s] : hi;
    }
    if (!(hi - lo > CALLGRIND_AGREE * lo))
        return NULL;
    return dm_xasprintf("Instructions of %s: the %d samples disagree by %.2g (%.0f .. %.0f per frame; "
                        "more than %.0e): the count is not repeatable here, see docs/counters.md",
                        c->key, CALLGRIND_SAMPLES, (hi - lo) / lo, lo, hi, CALLGRIND_AGREE);
}

/* 1 when callgrind's function name fn (up to len chars; a "'N" recursion
 * suffix ignored) is one of the C allocator's entry points. */
static int cg__allocator_name(const char *fn, size_t len)
{
    static const char *const names[] = {"malloc", "free", "calloc", "realloc", "reallocarray",
                                        "memalign", "posix_memalign", "aligned_alloc", "valloc",
                                        "pvalloc", "malloc_usable_size"};
    const char *q = memchr(fn, '\'', len);
    len = q ? (size_t)(q - fn) : len;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strlen(names[i]) == len && memcmp(names[i], fn, len) == 0)
            return 1;
    return 0;
}

/* The ids (callgrind's "fn=(ID) name" compression) of allocator functions. */
typedef struct cg_ids {
    long *id;
    size_t n, cap;
} cg_ids;

static int cg__ids_has(const cg_ids *ids, long id)
{
    for (size_t i = 0; i < ids->n; i++)
        if (ids->id[i] == id)
            return 1;
    return 0;
}

/* Whether the function named on a "fn=" or "cfn=" line (value v, up to the
 * end of the line) is an allocator function; learns compressed names. */
static int cg__fn_is_allocator(const char *v, size_t len, cg_ids *ids)
{
    if (len > 0 && v[0] == '(') {
        char *end = NULL;
        long id = strtol(v + 1, &end, 10);
        if (!end || *end != ')')
            return 0;
        const char *name = end + 1;
        if ((size_t)(name - v) < len && *name == ' ') {   /* first use: "(ID) name" */
            name++;
            int is = cg__allocator_name(name, len - (size_t)(name - v));
            if (is && !cg__ids_has(ids, id)) {
                if (ids->n == ids->cap) {
                    ids->cap = ids->cap ? 2 * ids->cap : 16;
                    ids->id = dm_xrealloc(ids->id, ids->cap * sizeof *ids->id);
                }
                ids->id[ids->n++] = id;
            }
            return is;
        }
        return cg__ids_has(ids, id);
    }
    return cg__allocator_name(v, len);
}

int callgrind_parse_dump(const char *text, char *name, size_t cap, double *totals, double *allocator)
{
    static const char trig[] = "desc: Trigger: Client Request: ";
    const char *t = strstr(text, trig), *tot = strstr(text, "\ntotals: ");
    if (!t || !tot || cap == 0)
        return DM_ERR_PARSE;
    t += sizeof trig - 1;
    size_t len = strcspn(t, "\n");
    if (len == 0 || len >= cap)
        return DM_ERR_PARSE;
    memcpy(name, t, len);
    name[len] = '\0';
    char *end = NULL;
    *totals = strtod(tot + 9, &end);
    if (end == tot + 9)
        return DM_ERR_PARSE;
    if (!allocator)
        return 0;
    /* The allocator's inclusive cost: every call from a function that is
     * not an allocator function into one ("cfn=", "calls=N POS", then the
     * line "POS INCLUSIVE"). */
    cg_ids ids = {0};
    int in_alloc = 0, to_alloc = 0, cost_next = 0;
    double sum = 0;
    for (const char *l = text; *l;) {
        size_t n = strcspn(l, "\n");
        if (cost_next) {
            cost_next = 0;
            const char *c = l + strcspn(l, " ");   /* after the position */
            if (to_alloc && !in_alloc && (size_t)(c - l) < n)
                sum += strtod(c, NULL);
        } else if (strncmp(l, "fn=", 3) == 0) {
            in_alloc = cg__fn_is_allocator(l + 3, n - 3, &ids);
        } else if (strncmp(l, "cfn=", 4) == 0) {
            to_alloc = cg__fn_is_allocator(l + 4, n - 4, &ids);
        } else if (strncmp(l, "calls=", 6) == 0) {
            cost_next = 1;
        }
        l += n + (l[n] == '\n');
    }
    free(ids.id);
    *allocator = sum;
    return 0;
}

/* ---- the parent side ------------------------------------------------------ */

typedef struct cg_state {
    const callgrind_desc *d;
    const plan_config *cs;
    size_t n;
    callgrind_count *out;
    int *tried, *done;
    int stages;              /* the sweep asks for the stage windows */
    char current[17];
    char *log;               /* the children's stderr (child.log; child.K.log for group K > 0) */
    char *changed;           /* a child found a source changed since the run started ('C') */
    pid_t pid;               /* the running child, or -1 */
    int fd;                  /* its stdout */
    dm_str buf;              /* its unfinished line */
    int64_t last;            /* when it last said something */
} cg_state;

static int cg__index(const cg_state *g, const char *key)
{
    for (size_t i = 0; i < g->n; i++)
        if (strcmp(g->cs[i].key, key) == 0)
            return (int)i;
    return -1;
}

/* Execs Valgrind on `dmbench __instructions SWEEP HASH [--source PATH
 * HASH]... KEY...` for the configurations not tried yet (a --source for
 * each user technique's file, with the hash of the text the run measures);
 * stdout is the pipe *fd. */
static pid_t cg__spawn(cg_state *g, int *fd)
{
    const callgrind_desc *d = g->d;
    char **argv = dm_xcalloc(g->n + 16 + 3 * user_technique_count(), sizeof *argv);
    size_t a = 0;
    char hash[17];
    dm_hex64(d->sweep->hash, hash);
    argv[a++] = dm_xstrdup(d->valgrind);
    argv[a++] = dm_xstrdup("--tool=callgrind");
    argv[a++] = dm_xstrdup("--collect-atstart=no");    /* only the frames between the toggles */
    argv[a++] = dm_xstrdup("--instr-atstart=no");      /* set-up, JIT and warm-up run uninstrumented */
    argv[a++] = dm_xstrdup("--smc-check=all-non-file"); /* llvmpipe writes JIT code to the heap */
    argv[a++] = dm_xasprintf("--callgrind-out-file=%s/cg.%%p.out", d->work_dir);
    argv[a++] = dm_xasprintf("--log-file=%s/valgrind.%%p.log", d->work_dir);
    /* no gdbserver: nothing attaches to a counting child, whose polling
     * for one cost time, and whose FIFOs a killed child left in /tmp */
    argv[a++] = dm_xstrdup("--vgdb=no");
    char self[4096] = "";
    ssize_t sl = d->self ? -1 : readlink("/proc/self/exe", self, sizeof self - 1);
    if (sl > 0)
        self[sl] = '\0';
    /* resolved here: after exec, /proc/self/exe would name Valgrind */
    argv[a++] = dm_xstrdup(d->self ? d->self : self);
    argv[a++] = dm_xstrdup("__instructions");
    argv[a++] = dm_xstrdup(d->sweep->path);
    argv[a++] = dm_xstrdup(hash);
    for (size_t i = 0; i < user_technique_count(); i++) {
        char source[17];
        dm_hex64(user_technique_at(i)->source_hash, source);
        argv[a++] = dm_xstrdup("--source");
        argv[a++] = dm_xstrdup(user_technique_path(user_technique_at(i)));
        argv[a++] = dm_xstrdup(source);
    }
    for (size_t i = 0; i < g->n; i++)
        if (!g->tried[i])
            argv[a++] = dm_xstrdup(g->cs[i].key);
    int fds[2] = {-1, -1};
    /* Valgrind keeps the parent-death signal across exec: the counting
     * child dies with the run, whose loop is its watchdog. */
    pid_t pid = pipe(fds) == 0 ? dm_proc_fork() : -1;
    if (pid == 0) {
        dup2(fds[1], 1);
        close(fds[0]);
        close(fds[1]);
        int lfd = open(g->log, O_WRONLY | O_CREAT | O_APPEND, 0644);
        if (lfd >= 0)
            dup2(lfd, 2);
        setenv("LP_NUM_THREADS", "0", 1);   /* rasteriser on the calling thread */
        /* Every symbol bound at load: lazy binding resolves a library
         * function at its first call, which a configuration pays or not
         * depending on what ran before it (docs/counters.md). */
        setenv("LD_BIND_NOW", "1", 1);
        execv(argv[0], argv);
        dprintf(1, "X cannot execute %s: %s\n", argv[0], strerror(errno));
        _exit(127);
    }
    for (size_t i = 0; i < a; i++)
        free(argv[i]);
    free(argv);
    if (pid > 0) {
        close(fds[1]);
        *fd = fds[0];
    } else if (fds[0] >= 0) {   /* the pipe, but no child */
        int e = errno;
        close(fds[0]);
        close(fds[1]);
        errno = e;
    }
    return pid;
}

/* Appends the last `keep` non-empty lines of file path (Valgrind's
 * "==PID==" prefixes and banner removed) to out, " | "-separated. */
static void cg__tail(const char *path, size_t keep, dm_str *out)
{
    char *text = NULL;
    size_t len = 0;
    if (dm_read_file(path, &text, &len) != 0 || !text)
        return;
    const char *lines[8] = {0};
    size_t k = 0;
    char *save = NULL;
    keep = keep > 8 ? 8 : keep;
    for (char *l = strtok_r(text, "\n", &save); l; l = strtok_r(NULL, "\n", &save)) {
        char *p = l[0] == '=' && l[1] == '=' ? strstr(l + 2, "== ") : NULL;
        l = p ? p + 3 : l;
        if (*l && !strstr(l, "Copyright") && !strstr(l, "Using Valgrind") && !strstr(l, "Command:") &&
            !strstr(l, "Callgrind, a call-graph"))
            lines[k++ % 8] = l;
    }
    for (size_t i = k > keep ? k - keep : 0; i < k; i++)
        dm_str_printf(out, "%s%s", out->len ? " | " : "", lines[i % 8]);
    free(text);
}

/* What Valgrind (its log of process pid) and the child (its stderr, shared
 * by its group's children) said last, or NULL. */
static char *cg__valgrind_message(const cg_state *g, pid_t pid)
{
    dm_str s = {0};
    char *vlog = dm_xasprintf("%s/valgrind.%d.log", g->d->work_dir, (int)pid);
    cg__tail(vlog, 5, &s);
    cg__tail(g->log, 2, &s);
    free(vlog);
    return s.len ? dm_str_take(&s) : (dm_str_free(&s), NULL);
}

static void cg__line(cg_state *g, char *line)
{
    char key[17] = "", status[16] = "";
    int off = 0;
    if (sscanf(line, "B %16s", key) == 1 && cg__index(g, key) >= 0) {
        snprintf(g->current, sizeof g->current, "%s", key);
        g->tried[cg__index(g, key)] = 1;
    } else if (sscanf(line, "W %16s", key) == 1 && cg__index(g, key) >= 0) {
        /* preparing it for its batch (run/count_child.c): a crash now fails
         * it alone, and a new child takes the batch's others, not counted yet */
        snprintf(g->current, sizeof g->current, "%s", key);
    } else if (sscanf(line, "S %16s %15s %n", key, status, &off) >= 2 && cg__index(g, key) >= 0) {
        int i = cg__index(g, key);
        if (strcmp(status, "ok") != 0 && !g->out[i].stage_reason)
            g->out[i].stage_reason = dm_xstrdup(off ? line + off : status);
    } else if (sscanf(line, "I %16s %15s %n", key, status, &off) >= 2 && cg__index(g, key) >= 0) {
        int i = cg__index(g, key);
        g->done[i] = 1;
        if (strcmp(status, "ok") != 0 && !g->out[i].reason)
            g->out[i].reason = dm_xasprintf("not counted: %s", off ? line + off : status);
        g->current[0] = '\0';
    } else if (line[0] == 'C' && line[1] == ' ' && !g->changed) {
        g->changed = dm_xstrdup(line + 2);
    }
}

/* Reads what child g->pid has written; returns 0 at its end of output. */
static int cg__read_lines(cg_state *g)
{
    char chunk[1024];
    ssize_t got = read(g->fd, chunk, sizeof chunk);
    if (got <= 0)
        return 0;
    g->last = dm_now_ns();
    for (ssize_t i = 0; i < got; i++) {
        if (chunk[i] != '\n') {
            dm_str_catn(&g->buf, &chunk[i], 1);
            continue;
        }
        char *line = dm_str_take(&g->buf);
        cg__line(g, line);
        free(line);
    }
    return 1;
}

/* Fails configuration i (the child was on it) with Valgrind's message. */
static void cg__fail(cg_state *g, int i, pid_t pid, int status)
{
    char *vg = cg__valgrind_message(g, pid);
    char how[96];
    if (status < 0)
        snprintf(how, sizeof how, "the Valgrind child made no progress for %.0f s (killed)", g->d->timeout_s);
    else if (WIFSIGNALED(status))
        snprintf(how, sizeof how, "the Valgrind child died of signal %d", WTERMSIG(status));
    else
        snprintf(how, sizeof how, "the Valgrind child exited with status %d", WEXITSTATUS(status));
    free(g->out[i].reason);
    g->out[i].failed = 1;
    g->out[i].reason = dm_xasprintf("Instructions: %s%s%s", how, vg ? "; valgrind: " : "", vg ? vg : "");
    g->tried[i] = 1;
    free(vg);
}

int callgrind_path_frames(const plan_config *c, int *step)
{
    size_t f = path_timing_frames(c);
    if (!f) {
        *step = 1;
        return CALLGRIND_FRAMES;
    }
    size_t k = (f + CALLGRIND_PATH_FRAMES - 1) / CALLGRIND_PATH_FRAMES;
    *step = (int)k;
    return (int)((f + k - 1) / k);
}

/* Reads every dump file of the work directory into out[].samples, per
 * frame: divided by the frames its configuration counted
 * (callgrind_path_frames). */
static void cg__read_dumps(cg_state *g)
{
    DIR *dir = opendir(g->d->work_dir);
    struct dirent *e;
    while (dir && (e = readdir(dir))) {
        if (strncmp(e->d_name, "cg.", 3) != 0 || !strstr(e->d_name, ".out."))
            continue;
        char *path = dm_xasprintf("%s/%s", g->d->work_dir, e->d_name), *text = NULL, name[64];
        size_t len = 0;
        double totals = NAN, alloc = 0;
        if (dm_read_file(path, &text, &len) == 0 &&
            callgrind_parse_dump(text, name, sizeof name, &totals, &alloc) == 0) {
            char *dot = strrchr(name, '.');
            int s = dot ? atoi(dot + 1) : -1, i = -1, w = CALLGRIND_FULL;
            if (dot) {
                *dot = '\0';
                size_t nl = strlen(name);   /* "KEY.g", "KEY.r", "KEY.m": a stage window */
                if (nl > 2 && name[nl - 2] == '.') {
                    const char *tags = "grm", *t = strchr(tags, name[nl - 1]);
                    w = t ? CALLGRIND_GEOMETRY + (int)(t - tags) : -1;
                    name[nl - 2] = '\0';
                }
                i = w >= 0 ? cg__index(g, name) : -1;
            }
            if (i >= 0 && s >= 0 && s < CALLGRIND_SAMPLES) {
                int step, frames = callgrind_path_frames(&g->cs[i], &step);
                g->out[i].window[w][s] = (totals - alloc) / frames;   /* the allocator left out */
                if (w == CALLGRIND_FULL) {
                    g->out[i].samples[s] = (totals - alloc) / frames;
                    g->out[i].allocator[s] = alloc / frames;
                }
            }
        }
        free(text);
        free(path);
    }
    if (dir)
        closedir(dir);
}

/* A configuration is counted when the child said ok and every sample's
 * dump was read. */
static void cg__settle(cg_state *g)
{
    for (size_t i = 0; i < g->n; i++) {
        callgrind_count *c = &g->out[i];
        int all = 1;
        for (int s = 0; s < CALLGRIND_SAMPLES; s++)
            all &= c->samples[s] > 0;
        c->counted = g->done[i] && !c->reason && all;
        if (!c->counted && !c->reason)
            c->reason = dm_xstrdup(g->tried[i] ? "Instructions: no callgrind dump for this configuration"
                                               : "Instructions: the Valgrind child did not reach it");
        if (!g->stages)
            continue;
        int windows = 1;
        for (int w = CALLGRIND_GEOMETRY; w < CALLGRIND_WINDOWS; w++)
            for (int s = 0; s < CALLGRIND_SAMPLES; s++)
                windows &= c->window[w][s] > 0;
        c->staged = c->counted && !c->stage_reason && windows;
        if (!c->staged && !c->stage_reason)
            c->stage_reason = dm_xstrdup(c->counted ? "no stage-window dump for this configuration"
                                                    : c->reason);
    }
}

/* Starts a child for the configurations of g not tried yet; -1 when it
 * cannot be started. */
static int cg__start(cg_state *g)
{
    g->current[0] = '\0';
    g->pid = cg__spawn(g, &g->fd);
    g->last = dm_now_ns();
    return g->pid < 0 ? -1 : 0;
}

/* Child g->pid has ended with wait status `status` (-1: the watchdog killed
 * it).  Unless it exited cleanly, the configuration it was on fails, or
 * every one not reached when it had not started one.  Returns 1 when a new
 * child should take the configurations left. */
static int cg__ended(cg_state *g, int status)
{
    int clean = status >= 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    int cur = g->current[0] ? cg__index(g, g->current) : -1;
    if (!clean && !g->changed)   /* a changed source stops the run: no configuration failed */
        for (size_t i = 0; i < g->n; i++)   /* the one it was on, or all when it never started one */
            if (!g->done[i] && (cur < 0 ? !g->tried[i] : (int)i == cur))
                cg__fail(g, (int)i, g->pid, status);
    close(g->fd);
    g->pid = -1;
    dm_str_free(&g->buf);
    size_t left = 0;
    for (size_t i = 0; i < g->n; i++)
        left += !g->tried[i] && !g->done[i];
    return !clean && !g->changed && left > 0;
}

/* Progress on stderr (unless quiet): "k of n counted", at most once a
 * second and when the last one is done; rewritten in place on a terminal,
 * where `final` ends the line the children left unfinished. */
typedef struct cg_progress { size_t shown; int64_t t0, last; int tty, open; } cg_progress;

static void cg__progress(const cg_state *gs, size_t ng, cg_progress *p, int final)
{
    if (gs[0].d->quiet)
        return;
    size_t done = 0, n = 0;
    for (size_t k = 0; k < ng; k++)
        for (size_t i = 0; i < gs[k].n; i++, n++)
            done += gs[k].done[i] || gs[k].out[i].failed;
    int64_t now = dm_now_ns();
    if (final) {
        if (p->open)
            fputc('\n', stderr);
        return;
    }
    if (done == p->shown || (done < n && now - p->last < 1000000000))
        return;
    p->open = p->tty && done < n;
    fprintf(stderr, "%sdmbench: instructions: %zu of %zu configurations counted (%.0f s)%s",
            p->tty ? "\r\033[K" : "", done, n, (double)(now - p->t0) / 1e9, p->open ? "" : "\n");
    p->shown = done;
    p->last = now;
}

/* 1 when a child of a group found a source changed since the run started. */
static int cg__changed(const cg_state *gs, size_t ng)
{
    for (size_t k = 0; k < ng; k++)
        if (gs[k].changed)
            return 1;
    return 0;
}

/* Runs the groups' children side by side until every group is done: one
 * poll over their outputs, each with its own watchdog.  Returns 0, or the
 * errno of a child that could not be started (the others are killed). */
static int cg__run_groups(cg_state *gs, size_t ng)
{
    cg_progress prog = { .t0 = dm_now_ns(), .tty = isatty(2) };
    struct pollfd *pfd = dm_xcalloc(ng, sizeof *pfd);
    size_t *who = dm_xcalloc(ng, sizeof *who);
    int rc = 0;
    for (size_t k = 0; k < ng && rc == 0; k++)
        rc = cg__start(&gs[k]) ? (errno ? errno : EAGAIN) : 0;
    while (rc == 0 && !cg__changed(gs, ng)) {   /* a changed source stops every child (below) */
        size_t nf = 0;
        for (size_t k = 0; k < ng; k++)
            if (gs[k].pid > 0) {
                pfd[nf] = (struct pollfd){gs[k].fd, POLLIN, 0};
                who[nf++] = k;
            }
        if (nf == 0)
            break;
        int ready = poll(pfd, (nfds_t)nf, 500);
        for (size_t j = 0; j < nf && rc == 0; j++) {
            cg_state *g = &gs[who[j]];
            int alive = ready > 0 && pfd[j].revents ? cg__read_lines(g) : 1, killed = 0;
            if (alive && (double)(dm_now_ns() - g->last) / 1e9 > g->d->timeout_s) {
                kill(g->pid, SIGKILL);   /* no progress: the watchdog */
                alive = 0;
                killed = 1;
            }
            if (alive)
                continue;
            int status = 0;
            waitpid(g->pid, &status, 0);
            if (cg__ended(g, killed ? -1 : status) && cg__start(g) != 0)
                rc = errno ? errno : EAGAIN;
        }
        cg__progress(gs, ng, &prog, 0);
    }
    cg__progress(gs, ng, &prog, 1);
    for (size_t k = 0; k < ng; k++)   /* after a failed start: stop the rest */
        if (gs[k].pid > 0) {
            kill(gs[k].pid, SIGKILL);
            waitpid(gs[k].pid, NULL, 0);
            close(gs[k].fd);
            dm_str_free(&gs[k].buf);
        }
    free(pfd);
    free(who);
    return rc;
}

/* MemAvailable of /proc/meminfo in GiB, or a large number when unknown. */
static double cg__available_gib(void)
{
    FILE *f = fopen("/proc/meminfo", "r");
    char line[128];
    double kib = -1;
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, "MemAvailable: %lf kB", &kib) == 1)
            break;
    if (f)
        fclose(f);
    return kib > 0 ? kib / (1024.0 * 1024.0) : 1e9;
}

int callgrind_env_jobs(dm_str *err)
{
    const char *v = getenv(CALLGRIND_JOBS_ENV);
    if (!v || !*v)
        return 0;
    char *end = NULL;
    errno = 0;
    long j = strtol(v, &end, 10);
    if (errno || end == v || *end || j < 0 || j > 256) {
        dm_str_printf(err, "%s=%s: not a whole number of counting children in 0..256 (0 or unset: one "
                      "per CPU; `run --count-jobs N` overrides it)", CALLGRIND_JOBS_ENV, v);
        return -1;
    }
    return (int)j;
}

int callgrind_jobs(int asked, size_t n)
{
    if (asked <= 0) {
        dm_str ignored = {0};
        int env = callgrind_env_jobs(&ignored);   /* refused at start-up (cli_main) when bad */
        dm_str_free(&ignored);
        asked = env > 0 ? env : 0;
    }
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    long j = asked > 0 ? asked : cpus > CALLGRIND_MAX_JOBS ? CALLGRIND_MAX_JOBS : cpus;
    if (asked <= 0) {   /* no more children than the memory holds */
        long fit = (long)(cg__available_gib() / CALLGRIND_JOB_GIB);
        j = j > fit ? fit : j;
    }
    j = j < 1 ? 1 : j;
    return (int)((size_t)j > n ? (n ? n : 1) : (size_t)j);
}

int callgrind_run(const callgrind_desc *d, const plan_config *cs, size_t n, callgrind_count *out,
                  dm_str *err)
{
    if (dm_mkdirs(d->work_dir) != 0) {
        dm_str_printf(err, "%s: cannot create the callgrind directory", d->work_dir);
        return DM_ERR_IO;
    }
    int stages = callgrind_wants_stages(&d->sweep->measure);
    size_t ng = (size_t)callgrind_jobs(d->jobs, n);
    /* Configuration i goes to group i mod ng (the --seed's order dealt
     * round, so each group gets a like mix); a count does not depend on
     * which child, or which others, it shares (docs/counters.md). */
    cg_state *gs = dm_xcalloc(ng, sizeof *gs);
    for (size_t k = 0; k < ng; k++) {
        size_t m = n / ng + (k < n % ng);
        plan_config *gcs = dm_xcalloc(m + 1, sizeof *gcs);
        for (size_t j = 0; j < m; j++)
            gcs[j] = cs[k + j * ng];   /* shallow: read only */
        gs[k] = (cg_state){ .d = d, .cs = gcs, .n = m, .stages = stages, .pid = -1, .fd = -1,
                            .out = dm_xcalloc(m + 1, sizeof *gs[k].out),
                            .tried = dm_xcalloc(m + 1, sizeof *gs[k].tried),
                            .done = dm_xcalloc(m + 1, sizeof *gs[k].done),
                            .log = k ? dm_xasprintf("%s/child.%zu.log", d->work_dir, k)
                                     : dm_xasprintf("%s/child.log", d->work_dir) };
    }
    int rc = 0, e = cg__run_groups(gs, ng);
    if (e != 0) {
        dm_str_printf(err, "cannot start %s: %s", d->valgrind, strerror(e));
        rc = DM_ERR_CHILD;
    }
    for (size_t k = 0; k < ng && rc == 0; k++)
        if (gs[k].changed) {
            dm_str_cat(err, gs[k].changed);
            rc = DM_ERR_ARG;
        }
    cg_state g = { .d = d, .cs = cs, .n = n, .out = out, .stages = stages,
                   .tried = dm_xcalloc(n + 1, sizeof *g.tried), .done = dm_xcalloc(n + 1, sizeof *g.done) };
    for (size_t k = 0; k < ng; k++) {   /* the groups' results back in cs's order */
        for (size_t j = 0; j < gs[k].n; j++) {
            size_t i = k + j * ng;
            out[i] = gs[k].out[j];
            g.tried[i] = gs[k].tried[j];
            g.done[i] = gs[k].done[j];
        }
        free((void *)gs[k].cs);
        free(gs[k].out);
        free(gs[k].tried);
        free(gs[k].done);
        free(gs[k].log);
        free(gs[k].changed);
    }
    free(gs);
    for (size_t i = 0; i < n; i++)
        snprintf(out[i].key, sizeof out[i].key, "%s", cs[i].key);
    cg__read_dumps(&g);
    cg__settle(&g);
    free(g.tried);
    free(g.done);
    return rc;
}
