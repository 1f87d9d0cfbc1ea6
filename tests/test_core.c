/* Unit tests of core/: error names, exit codes, "did you mean", strings, HTML escaping, hashing, files,
 * child processes. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "core/dm_util.h"
#include "core/dm_table.h"

#include <math.h>
#include "core/dm_results.h"
#include "core/dm_proc.h"

#include <signal.h>
#include <stdio.h>
#include <sys/wait.h>
#include <time.h>

static void test_error_names(void **state)
{
    (void)state;
    assert_string_equal(dm_errname(DM_ERR_PARSE), "DM_ERR_PARSE");
    assert_string_equal(dm_strerror(DM_ERR_NOMEM), "out of memory");
    assert_string_equal(dm_errname(12345), "DM_ERR_?");
    assert_int_equal(DM_ERR_OK, 0);
}

static void test_str_and_html(void **state)
{
    (void)state;
    dm_str s = {0};
    assert_string_equal(dm_str_get(&s), "");
    dm_str_printf(&s, "%d-%s", 42, "x");
    dm_str_cat_html(&s, "<script>alert('1')&\"</script>");
    assert_string_equal(dm_str_get(&s),
        "42-x&lt;script&gt;alert(&#39;1&#39;)&amp;&quot;&lt;/script&gt;");
    char *t = dm_str_take(&s);
    assert_null(s.buf);
    free(t);
}

static void test_hash(void **state)
{
    (void)state;
    /* FNV-1a 64 of "a" is a published test vector. */
    assert_true(dm_fnv1a64("a", 1, DM_FNV_SEED) == 0xaf63dc4c8601ec8cULL);
    char hex[17];
    dm_hex64(0xaf63dc4c8601ec8cULL, hex);
    assert_string_equal(hex, "af63dc4c8601ec8c");
}

static void test_files(void **state)
{
    (void)state;
    char dir[] = "/tmp/dmcoreXXXXXX";
    assert_non_null(mkdtemp(dir));
    char *sub = dm_xasprintf("%s/a/b/c", dir);
    assert_int_equal(dm_mkdirs(sub), 0);
    char *f = dm_xasprintf("%s/x.txt", sub);
    assert_int_equal(dm_write_file(f, "hello", 5), 0);
    char *buf = NULL;
    size_t len = 0;
    assert_int_equal(dm_read_file(f, &buf, &len), 0);
    assert_int_equal(len, 5);
    assert_string_equal(buf, "hello");
    assert_int_equal(dm_read_file("/nonexistent/x", &buf, &len), DM_ERR_IO);
    assert_int_equal(dm_write_file("/nonexistent/dir/x", "a", 1), DM_ERR_IO);
    free(buf);
    free(f);
    free(sub);
    test_rm_rf(dir);
}

/* dm_write_file past a file-size limit (ulimit -f; SIGXFSZ ignored, as
 * dmbench does): DM_ERR_DISK with errno EFBIG, the old file kept as it was
 * and no temp file left beside it. */
static void test_write_file_disk(void **state)
{
    (void)state;
    char dir[] = "/tmp/dmcoreXXXXXX";
    assert_non_null(mkdtemp(dir));
    char *f = dm_xasprintf("%s/out.html", dir);
    assert_int_equal(dm_write_file(f, "old", 3), 0);
    static char big[65536];
    struct rlimit old, lim;
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &old), 0);
    lim = old;
    lim.rlim_cur = 4096;
    void (*prev)(int) = signal(SIGXFSZ, SIG_IGN);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
    int rc = dm_write_file(f, big, sizeof big), e = errno;
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &old), 0);
    signal(SIGXFSZ, prev);
    assert_int_equal(rc, DM_ERR_DISK);
    assert_int_equal(e, EFBIG);
    assert_int_equal(dm_exit_from_error(rc), DM_EXIT_ENV);
    char *buf = NULL;
    assert_int_equal(dm_read_file(f, &buf, NULL), 0);
    assert_string_equal(buf, "old");
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *de; (de = readdir(d)) != NULL;)
        n += de->d_name[0] != '.';
    closedir(d);
    assert_int_equal(n, 1);   /* out.html only: the temp file is gone */
    assert_int_equal(dm_write_file("/nonexistent/dir/x", "a", 1), DM_ERR_IO);
    assert_int_equal(errno, ENOENT);
    unlink(f);
    test_rm_rf(dir);
    free(buf);
    free(f);
}

/* dm_input_file: a regular file (also through a symlink) passes; a
 * directory, a device, a symlink to /dev/zero, a FIFO are refused without
 * being opened (a FIFO with no writer would block an open); a missing file
 * is DM_ERR_NOTFOUND; every refusal says why. */
static void test_input_file(void **state)
{
    (void)state;
    char dir[] = "/tmp/dmcoreXXXXXX", why[256];
    assert_non_null(mkdtemp(dir));
    char *f = dm_xasprintf("%s/a.png", dir), *ln = dm_xasprintf("%s/l.png", dir),
         *zero = dm_xasprintf("%s/z.exr", dir), *fifo = dm_xasprintf("%s/p.png", dir);
    assert_int_equal(dm_write_file(f, "x", 1), 0);
    assert_int_equal(symlink(f, ln), 0);
    assert_int_equal(symlink("/dev/zero", zero), 0);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    assert_int_equal(dm_input_file(f, why, sizeof why), 0);
    assert_int_equal(dm_input_file(ln, why, sizeof why), 0);
    const char *bad[] = { dir, "/dev/zero", zero, fifo };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        why[0] = 0;
        assert_int_equal(dm_input_file(bad[i], why, sizeof why), DM_ERR_ARG);
        assert_non_null(strstr(why, "not a regular file"));
    }
    assert_int_equal(dm_input_file("/nonexistent/x.png", why, sizeof why), DM_ERR_NOTFOUND);
    assert_string_equal(why, "No such file or directory");
    assert_int_equal(dm_input_file("", NULL, 0), DM_ERR_NOTFOUND);
    unlink(f);
    unlink(ln);
    unlink(zero);
    unlink(fifo);
    test_rm_rf(dir);
    free(f);
    free(ln);
    free(zero);
    free(fifo);
}

static void test_results_kv(void **state)
{
    (void)state;
    dm_kv *kv = NULL;
    size_t n = 0;
    dm_kv_push(&kv, &n, "technique", "normal");
    dm_kv_push(&kv, &n, "mesh", "plane");
    assert_string_equal(dm_kv_get(kv, n, "mesh"), "plane");
    assert_null(dm_kv_get(kv, n, "tess_level"));
    dm_kv_free(kv, n);
}

static void test_closest(void **state)
{
    (void)state;
    const char *const axes[] = { "tess_level", "tess_spacing", "technique", "mesh" };
    assert_string_equal(dm_closest("tess_levle", axes, 4), "tess_level");
    assert_string_equal(dm_closest("mesch", axes, 4), "mesh");
    assert_null(dm_closest("zzzzzzzz", axes, 4));
    dm_str s = {0};
    dm_str_cat_list(&s, axes, 2);
    assert_string_equal(dm_str_get(&s), "tess_level, tess_spacing");
    dm_str_free(&s);
}

static void test_exit_codes(void **state)
{
    (void)state;
    assert_int_equal(DM_EXIT_OK, 0);
    assert_int_equal(DM_EXIT_FAILED, 1);
    assert_int_equal(DM_EXIT_USAGE, 2);
    assert_int_equal(DM_EXIT_INCONCLUSIVE, 3);
    assert_int_equal(DM_EXIT_ENV, 4);
    assert_non_null(dm_exit_meaning(4));
    assert_null(dm_exit_meaning(5));
    assert_null(dm_exit_meaning(-1));
    assert_int_equal(dm_exit_from_error(0), DM_EXIT_OK);
    static const int usage[] = { DM_ERR_ARG, DM_ERR_PARSE, DM_ERR_RANGE, DM_ERR_UNKNOWN, DM_ERR_NOTFOUND,
                                 DM_ERR_EXISTS, DM_ERR_IO, DM_ERR_UNSUPPORTED };
    for (size_t i = 0; i < sizeof usage / sizeof *usage; i++)
        assert_int_equal(dm_exit_from_error(usage[i]), DM_EXIT_USAGE);
    static const int failed[] = { DM_ERR_SHADER, DM_ERR_NUMERIC, DM_ERR_TIMEOUT };
    for (size_t i = 0; i < sizeof failed / sizeof *failed; i++)
        assert_int_equal(dm_exit_from_error(failed[i]), DM_EXIT_FAILED);
    static const int env[] = { DM_ERR_STORE, DM_ERR_BUSY, DM_ERR_CHILD, DM_ERR_GL, DM_ERR_DISK,
                               DM_ERR_NOMEM };
    for (size_t i = 0; i < sizeof env / sizeof *env; i++)
        assert_int_equal(dm_exit_from_error(env[i]), DM_EXIT_ENV);
}

static void test_suggest(void **state)
{
    (void)state;
    static const char *const c[] = { "techniques", "textures", "axes" };
    dm_str s = {0};
    dm_str_cat(&s, "unknown list 'texturs'");
    dm_str_suggest(&s, "texturs", c, 3, "lists");
    assert_string_equal(dm_str_get(&s), "unknown list 'texturs'; did you mean 'textures'? "
                                        "valid lists: techniques, textures, axes");
    dm_str_free(&s);
    dm_str_suggest(&s, "zzzzzzzzzzzz", c, 3, "lists");
    assert_string_equal(dm_str_get(&s), "; valid lists: techniques, textures, axes");
    dm_str_free(&s);
}

static void proc__hello(int fd, void *arg)
{
    dprintf(fd, "hello %s", (const char *)arg);
}

static void proc__silent(int fd, void *arg)
{
    (void)fd;
    (void)arg;
    for (;;)
        pause();
}

static void proc__crash(int fd, void *arg)
{
    (void)arg;
    dprintf(fd, "K\n");
    signal(SIGSEGV, SIG_DFL);   /* cmocka's handler is inherited */
    raise(SIGSEGV);
}

/* A child of the child (both by dm_proc_fork) that reports its pid and
 * waits; its parent then exits. */
static void proc__orphan_maker(int fd, void *arg)
{
    (void)arg;
    pid_t g = dm_proc_fork();
    if (g == 0) {
        for (;;)
            pause();
    }
    dprintf(fd, "%ld\n", (long)g);
}

/* 1 when process pid is gone or a zombie. */
static int proc__gone(long pid)
{
    char path[64], st[256] = "";
    snprintf(path, sizeof path, "/proc/%ld/stat", pid);
    FILE *f = fopen(path, "r");
    if (!f)
        return 1;
    size_t n = fread(st, 1, sizeof st - 1, f);
    fclose(f);
    st[n] = '\0';
    const char *close = strrchr(st, ')');
    return close && close[1] == ' ' && close[2] == 'Z';
}

static void test_proc(void **state)
{
    (void)state;
    dm_proc_result r;
    /* what the child writes comes back, with its exit status */
    assert_int_equal(dm_proc_collect(proc__hello, "world", 10, &r), 0);
    assert_string_equal(r.text, "hello world");
    assert_true(r.started && !r.timed_out && WIFEXITED(r.status) && WEXITSTATUS(r.status) == 0);
    free(r.text);
    /* a silent child is stopped at the deadline */
    assert_int_equal(dm_proc_collect(proc__silent, NULL, 0.2, &r), -1);
    assert_true(r.timed_out && r.seconds >= 0.2 && r.seconds < 5);
    free(r.text);
    /* a crash is its signal, after what it said */
    assert_int_equal(dm_proc_collect(proc__crash, NULL, 10, &r), -1);
    assert_string_equal(r.text, "K\n");
    assert_true(!r.timed_out && WIFSIGNALED(r.status) && WTERMSIG(r.status) == SIGSEGV);
    free(r.text);
    /* a child whose parent ends dies with it (the parent-death signal) */
    assert_int_equal(dm_proc_collect(proc__orphan_maker, NULL, 10, &r), 0);
    long g = strtol(r.text, NULL, 10);
    free(r.text);
    assert_true(g > 0);
    int gone = 0;
    for (int i = 0; i < 200 && !(gone = proc__gone(g)); i++) {
        struct timespec t = { 0, 10000000 };
        nanosleep(&t, NULL);
    }
    if (!gone)
        kill((pid_t)g, SIGKILL);
    assert_true(gone);
}

/* Grouped counts and a table that wraps at its width, repeating the labels. */
static void test_table(void **state)
{
    (void)state;
    static const struct { double v; const char *want; } counts[] = {
        {0, "0"}, {640, "640"}, {999.6, "1\u202f000"}, {6144, "6\u202f144"},
        {3169024, "3\u202f169\u202f024"}, {-12345, "\u221212\u202f345"}, {NAN, "\u2013"}};
    for (size_t i = 0; i < sizeof counts / sizeof *counts; i++) {
        dm_str s = {0};
        dm_str_cat_count(&s, counts[i].v);
        assert_string_equal(dm_str_get(&s), counts[i].want);
        dm_str_free(&s);
    }
    assert_int_equal(dm_text_width("cube 480\u00d7270 \u00b7 pom"), 18);
    dm_table t = {0};
    dm_table_cell(&t, "cfg");
    dm_table_cell(&t, "AAAA");
    dm_table_cell(&t, "BBBB");
    dm_table_row(&t);
    dm_table_cell(&t, "p\u00d7");
    dm_table_cell(&t, "1");
    dm_table_cell(&t, "22");
    dm_str s = {0};
    dm_table_text(&t, "  ", 14, &s);   /* "  cfg  AAAA" is 11: BBBB goes to a second block */
    assert_string_equal(dm_str_get(&s), "  cfg  AAAA\n  ---------\n  p\u00d7      1\n"
                                        "\n  cfg  BBBB\n  ---------\n  p\u00d7     22\n");
    dm_str_free(&s);
    dm_table_text(&t, "", 100, &s);
    assert_string_equal(dm_str_get(&s), "cfg  AAAA  BBBB\n---------------\np\u00d7      1    22\n");
    dm_str_free(&s);
    dm_table_free(&t);
    /* dm_wrap: a lone "%" after a number stays on its line ("3.33 %" would
     * otherwise leave "%" alone on the next one) */
    dm_wrap("resolves: 3.33 % here", "", "  ", 14, &s);
    assert_string_equal(dm_str_get(&s), "resolves:\n  3.33 % here\n");
    dm_str_free(&s);
    dm_wrap("it resolves 3.33 %", "", "    ", 16, &s);
    assert_string_equal(dm_str_get(&s), "it resolves\n    3.33 %\n");
    dm_str_free(&s);
    dm_wrap("a  b", "> ", "  ", 80, &s);   /* runs of spaces still close up */
    assert_string_equal(dm_str_get(&s), "> a b\n");
    dm_str_free(&s);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_error_names),
             cmocka_unit_test(test_exit_codes),
             cmocka_unit_test(test_suggest),
             cmocka_unit_test(test_str_and_html),
             cmocka_unit_test(test_hash),
             cmocka_unit_test(test_files),
             cmocka_unit_test(test_write_file_disk),
             cmocka_unit_test(test_input_file),
             cmocka_unit_test(test_results_kv),
             cmocka_unit_test(test_closest),
             cmocka_unit_test(test_proc),
             cmocka_unit_test(test_table))
