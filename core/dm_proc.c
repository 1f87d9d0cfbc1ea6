/* dm_proc.c — child processes that die with their parent (see dm_proc.h). */
#include "dm_proc.h"
#include "dm_util.h"

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

pid_t dm_proc_fork(void)
{
    pid_t parent = getpid();
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        /* The parent may have died between fork() and prctl(): then no
         * signal would ever come, and the child is already an orphan. */
        if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != parent)
            raise(SIGKILL);
    }
    return pid;
}

pid_t dm_proc_wait(pid_t pid, int *status)
{
    pid_t r;
    int st = 0;
    while ((r = waitpid(pid, &st, 0)) < 0 && errno == EINTR)
        ;
    if (status)
        *status = st;
    return r;
}

int dm_proc_collect(void (*child)(int fd, void *arg), void *arg, double timeout_s,
                    dm_proc_result *out)
{
    *out = (dm_proc_result){0};
    int fds[2];
    if (pipe(fds) != 0) {
        out->status = errno;
        out->text = dm_xstrdup("");
        return -1;
    }
    int64_t t0 = dm_now_ns();
    pid_t pid = dm_proc_fork();
    if (pid == 0) {
        close(fds[0]);
        child(fds[1], arg);
        _exit(0);
    }
    close(fds[1]);
    if (pid < 0) {
        out->status = errno;
        close(fds[0]);
        out->text = dm_xstrdup("");
        return -1;
    }
    out->started = 1;
    dm_str s = {0};
    int64_t deadline = t0 + (int64_t)(timeout_s * 1e9);
    struct pollfd pfd = { fds[0], POLLIN, 0 };
    for (;;) {
        int64_t left = deadline - dm_now_ns();
        if (left <= 0) {
            out->timed_out = 1;
            break;
        }
        int pr = poll(&pfd, 1, (int)(left / 1000000 + 1));
        if (pr < 0 && errno == EINTR)
            continue;
        if (pr == 0)
            continue;   /* the deadline is checked above */
        char buf[4096];
        ssize_t n = pr > 0 ? read(fds[0], buf, sizeof buf) : -1;
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        dm_str_catn(&s, buf, (size_t)n);
        deadline = dm_now_ns() + (int64_t)(timeout_s * 1e9);   /* it is alive: a new period */
    }
    close(fds[0]);
    /* EOF: the child closed its end, normally by exiting; a child that
     * closed it and went on is stopped like one past its deadline. */
    if (out->timed_out || waitpid(pid, &out->status, WNOHANG) == 0) {
        struct timespec pause = { 0, 20000000 };
        int waited = 0;
        while (!out->timed_out && waited++ < 50 && waitpid(pid, &out->status, WNOHANG) == 0)
            nanosleep(&pause, NULL);   /* an exiting child: up to 1 s to be reaped */
        if (out->timed_out || waited > 50) {
            kill(pid, SIGKILL);
            dm_proc_wait(pid, &out->status);
            out->timed_out = 1;
        }
    }
    out->seconds = (double)(dm_now_ns() - t0) / 1e9;
    out->text = dm_str_take(&s);
    return !out->timed_out && WIFEXITED(out->status) && WEXITSTATUS(out->status) == 0 ? 0 : -1;
}
