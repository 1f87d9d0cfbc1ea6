/* dm_proc.h — the one way dmbench starts a child process
 * (docs/reliability.md, "Interruptions").
 *
 * Every child dies with the process that started it: dm_proc_fork() sets
 * the parent-death signal (SIGKILL) in the child before it does anything
 * else, and closes the race of a parent that died before that by comparing
 * getppid() with the parent's pid saved before fork().  The signal survives
 * execve(), so it holds for Valgrind, `dmbench run` started by `drivers`,
 * sbatch and every other program a child executes; a child's own children
 * started here die with it in turn, so killing any dmbench process (SIGTERM
 * or SIGKILL) takes its whole tree along.  The signal fires when the thread
 * that forked ends: dmbench forks from its main thread only.
 *
 * No watchdog may live only in a process that can die first: a parent that
 * waits for a child with a deadline (dm_proc_collect) is the child's
 * watchdog, and the child cannot outlive it.
 */
#ifndef CORE_DM_PROC_H
#define CORE_DM_PROC_H

#include <sys/types.h>

/* fork() whose child dies with this process (above).  Flushes stdio first
 * so the child repeats no buffered output.  Returns as fork() does: the
 * child's pid in the parent, 0 in the child, -1 with errno. */
pid_t dm_proc_fork(void);

/* waitpid() retried on EINTR.  Returns pid, or -1 with errno. */
pid_t dm_proc_wait(pid_t pid, int *status);

/* What a child run by dm_proc_collect did. */
typedef struct dm_proc_result {
    char *text;        /* everything it wrote to its descriptor (NUL-terminated; caller frees) */
    int status;        /* its wait status; meaningful when !timed_out */
    int timed_out;     /* it was silent for timeout_s (or did not exit) and was killed */
    int started;       /* 0: fork or pipe failed (errno in status) */
    double seconds;    /* how long it ran */
} dm_proc_result;

/* Runs child(fd, arg) in a child process (dm_proc_fork) that exits 0 when
 * it returns, and collects what it writes to fd until it closes fd or exits,
 * or until it has written nothing for timeout_s seconds (the watchdog: a
 * child that reports each step gets timeout_s for each); then kills it
 * (SIGKILL) if it still runs and reaps it.  Always fills *out (started 0 when no child could be
 * made).  Returns 0 when the child exited 0 within the deadline, else -1. */
int dm_proc_collect(void (*child)(int fd, void *arg), void *arg, double timeout_s,
                    dm_proc_result *out);

#endif
