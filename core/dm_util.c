#include "dm_util.h"
#include "dm_error.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static enum dm_log_level g_log_level = DM_LOG_INFO;

void dm_log_set_level(enum dm_log_level level) { g_log_level = level; }
enum dm_log_level dm_log_get_level(void) { return g_log_level; }

void dm_log(enum dm_log_level level, const char *fmt, ...)
{
    static const char *names[] = { "error", "warning", "info", "debug" };
    if (level > g_log_level)
        return;
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "dmbench: %s: ", names[level]);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

static void dm__oom(size_t n)
{
    fprintf(stderr, "dmbench: error: out of memory allocating %zu bytes\n", n);
    abort();
}

void *dm_xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p)
        dm__oom(n);
    return p;
}

void *dm_xcalloc(size_t count, size_t n)
{
    void *p = calloc(count ? count : 1, n ? n : 1);
    if (!p)
        dm__oom(count * n);
    return p;
}

void *dm_xrealloc(void *p, size_t n)
{
    void *q = realloc(p, n ? n : 1);
    if (!q)
        dm__oom(n);
    return q;
}

char *dm_xstrdup(const char *s)
{
    if (!s)
        return NULL;
    size_t n = strlen(s) + 1;
    char *d = dm_xmalloc(n);
    memcpy(d, s, n);
    return d;
}

char *dm_xasprintf(const char *fmt, ...)
{
    dm_str s = {0};
    va_list ap;
    va_start(ap, fmt);
    dm_str_vprintf(&s, fmt, ap);
    va_end(ap);
    return dm_str_take(&s);
}

static void dm__str_reserve(dm_str *s, size_t extra)
{
    if (s->len + extra + 1 <= s->cap)
        return;
    size_t cap = s->cap ? s->cap : 64;
    while (cap < s->len + extra + 1)
        cap *= 2;
    s->buf = dm_xrealloc(s->buf, cap);
    s->cap = cap;
}

void dm_str_catn(dm_str *s, const char *text, size_t n)
{
    dm__str_reserve(s, n);
    memcpy(s->buf + s->len, text, n);
    s->len += n;
    s->buf[s->len] = '\0';
}

void dm_str_cat(dm_str *s, const char *text) { dm_str_catn(s, text, strlen(text)); }

void dm_str_vprintf(dm_str *s, const char *fmt, va_list ap)
{
    va_list ap2;
    va_copy(ap2, ap);
    char probe[1];
    int n = vsnprintf(probe, sizeof probe, fmt, ap2);   /* length only */
    va_end(ap2);
    if (n < 0)
        return;
    dm__str_reserve(s, (size_t)n);
    vsnprintf(s->buf + s->len, (size_t)n + 1, fmt, ap);
    s->len += (size_t)n;
}

void dm_str_printf(dm_str *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    dm_str_vprintf(s, fmt, ap);
    va_end(ap);
}

void dm_str_cat_html(dm_str *s, const char *text)
{
    for (const char *p = text ? text : ""; *p; p++) {
        switch (*p) {
        case '&': dm_str_cat(s, "&amp;"); break;
        case '<': dm_str_cat(s, "&lt;"); break;
        case '>': dm_str_cat(s, "&gt;"); break;
        case '"': dm_str_cat(s, "&quot;"); break;
        case '\'': dm_str_cat(s, "&#39;"); break;
        default: dm_str_catn(s, p, 1);
        }
    }
}

const char *dm_str_get(const dm_str *s) { return s->buf ? s->buf : ""; }

char *dm_str_take(dm_str *s)
{
    char *b = s->buf ? s->buf : dm_xstrdup("");
    s->buf = NULL;
    s->len = s->cap = 0;
    return b;
}

void dm_str_free(dm_str *s)
{
    free(s->buf);
    s->buf = NULL;
    s->len = s->cap = 0;
}

static int64_t dm__clock(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (int64_t)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

int64_t dm_now_ns(void) { return dm__clock(CLOCK_MONOTONIC); }
int64_t dm_cpu_ns(void) { return dm__clock(CLOCK_PROCESS_CPUTIME_ID); }
int64_t dm_thread_cpu_ns(void) { return dm__clock(CLOCK_THREAD_CPUTIME_ID); }

void dm_iso8601_now(char buf[32])
{
    time_t t = time(NULL);
    struct tm tm;
    gmtime_r(&t, &tm);
    strftime(buf, 32, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

uint64_t dm_fnv1a64(const void *data, size_t n, uint64_t seed)
{
    const unsigned char *p = data;
    uint64_t h = seed;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0x100000001b3ULL;
    }
    return h;
}

void dm_hex64(uint64_t h, char out[17])
{
    snprintf(out, 17, "%016llx", (unsigned long long)h);
}

int dm_read_stream(FILE *f, dm_str *out)
{
    char chunk[65536];
    size_t n;
    while ((n = fread(chunk, 1, sizeof chunk, f)) > 0)
        dm_str_catn(out, chunk, n);
    return ferror(f) ? DM_ERR_IO : 0;
}

int dm_read_file(const char *path, char **out, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return DM_ERR_IO;
    dm_str s = {0};
    int bad = dm_read_stream(f, &s);
    fclose(f);
    if (bad) {
        dm_str_free(&s);
        return DM_ERR_IO;
    }
    if (len)
        *len = s.len;
    *out = dm_str_take(&s);
    return 0;
}

int dm_disk_errno(int e)
{
    return e == ENOSPC || e == EFBIG || e == EIO
#ifdef EDQUOT
           || e == EDQUOT
#endif
        ;
}

int dm_write_file(const char *path, const void *data, size_t len)
{
    char *tmp = dm_xasprintf("%s.tmp.%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "wb");
    int e = 0;
    if (!f) {
        e = errno;
        goto err;
    }
    if (fwrite(data, 1, len, f) != len || fflush(f) != 0) {
        e = errno;
        fclose(f);
        goto err_unlink;
    }
    if (fclose(f) != 0 || rename(tmp, path) != 0) {
        e = errno;
        goto err_unlink;
    }
    free(tmp);
    return 0;
err_unlink:
    unlink(tmp);
err:
    free(tmp);
    errno = e ? e : EIO;
    return dm_disk_errno(errno) ? DM_ERR_DISK : DM_ERR_IO;
}

int dm_mkdirs(const char *path)
{
    char *p = dm_xstrdup(path);
    for (char *q = p + 1; *q; q++) {
        if (*q != '/')
            continue;
        *q = '\0';
        if (mkdir(p, 0777) != 0 && errno != EEXIST) {
            free(p);
            return DM_ERR_IO;
        }
        *q = '/';
    }
    int rc = (mkdir(p, 0777) == 0 || errno == EEXIST) ? 0 : DM_ERR_IO;
    free(p);
    return rc;
}

int dm_file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static size_t dm__edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    size_t *row = dm_xmalloc((lb + 1) * sizeof *row);
    for (size_t j = 0; j <= lb; j++)
        row[j] = j;
    for (size_t i = 1; i <= la; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= lb; j++) {
            size_t up = row[j];
            size_t cost = tolower((unsigned char)a[i - 1]) == tolower((unsigned char)b[j - 1]) ? 0 : 1;
            size_t best = diag + cost;
            if (row[j] + 1 < best)
                best = row[j] + 1;
            if (row[j - 1] + 1 < best)
                best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    size_t d = row[lb];
    free(row);
    return d;
}

const char *dm_closest(const char *word, const char *const *choices, size_t n)
{
    size_t limit = strlen(word) / 3 > 2 ? strlen(word) / 3 : 2;
    const char *best = NULL;
    size_t best_d = limit + 1;
    for (size_t i = 0; i < n; i++) {
        size_t d = dm__edit_distance(word, choices[i]);
        if (d < best_d) {
            best_d = d;
            best = choices[i];
        }
    }
    return best;
}

void dm_str_cat_list(dm_str *s, const char *const *choices, size_t n)
{
    for (size_t i = 0; i < n; i++)
        dm_str_printf(s, "%s%s", i ? ", " : "", choices[i]);
}

int dm_split_paths(const char *list, const char *what, char ***items, size_t *n, dm_str *err)
{
    struct stat st;
    *items = NULL;
    *n = 0;
    if (list && *list && stat(list, &st) == 0) {
        DM_VEC_PUSH(*items, *n, dm_xstrdup(list));
        return 0;
    }
    const char *p = list ? list : "";
    for (;;) {
        size_t len = strcspn(p, ",");
        if (len == 0) {
            dm_str_printf(err, "%s '%s': %s; give PATH[,PATH...]",
                          what, list ? list : "", *p || *n ? "an empty entry" : "no path");
            dm_strv_free(*items, *n);
            *items = NULL;
            *n = 0;
            return DM_ERR_ARG;
        }
        char *item = dm_xmalloc(len + 1);
        memcpy(item, p, len);
        item[len] = '\0';
        DM_VEC_PUSH(*items, *n, item);
        if (!p[len])
            return 0;
        p += len + 1;
    }
}

void dm_strv_free(char **v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(v[i]);
    free(v);
}

void dm_str_suggest(dm_str *s, const char *word, const char *const *choices, size_t n,
                    const char *what)
{
    const char *close = word ? dm_closest(word, choices, n) : NULL;
    if (close)
        dm_str_printf(s, "; did you mean '%s'?", close);
    else
        dm_str_cat(s, ";");
    dm_str_printf(s, " valid %s: ", what);
    dm_str_cat_list(s, choices, n);
}

void dm_str_expected(dm_str *s, const char *value, const char *const *choices, size_t n)
{
    const char *close = value ? dm_closest(value, choices, n) : NULL;
    dm_str_cat(s, "expected one of: ");
    dm_str_cat_list(s, choices, n);
    if (close)
        dm_str_printf(s, " (did you mean '%s'?)", close);
}

int dm_input_file(const char *path, char *why, size_t whylen)
{
    struct stat st;
    const char *reason = NULL;
    int rc = 0;
    if (!path || !*path) {
        reason = "no file named (an empty path)";
        rc = DM_ERR_NOTFOUND;
    } else if (stat(path, &st) != 0) {
        reason = strerror(errno);
        rc = errno == ENOENT || errno == ENOTDIR ? DM_ERR_NOTFOUND : DM_ERR_IO;
    } else if (!S_ISREG(st.st_mode)) {
        reason = "not a regular file (a directory, FIFO or device)";
        rc = DM_ERR_ARG;
    }
    if (rc && why && whylen)
        snprintf(why, whylen, "%s", reason);
    return rc;
}

const char *dm_nomem_reason(char *buf, size_t len)
{
    struct rlimit as;
    if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
        snprintf(buf, len, "out of memory under the address-space limit of %llu MB (ulimit -v %llu)",
                 (unsigned long long)(as.rlim_cur >> 20), (unsigned long long)(as.rlim_cur >> 10));
    else
        snprintf(buf, len, "out of memory");
    return buf;
}

void dm_str_cat_md(dm_str *s, const char *text)
{
    for (const unsigned char *p = (const unsigned char *)(text ? text : ""); *p; p++) {
        const char *rep = *p == '|' ? "\\|" : *p == '<' ? "&lt;" : *p == '>' ? "&gt;"
                        : *p == '&' ? "&amp;" : *p == '`' ? "'" : *p == '\n' || *p == '\r' ? " "
                        : *p < 0x20 || *p == 0x7f ? "?" : NULL;
        if (rep)
            dm_str_cat(s, rep);
        else
            dm_str_catn(s, (const char *)p, 1);
    }
}

void dm_str_cat_term(dm_str *s, const char *text)
{
    for (const unsigned char *p = (const unsigned char *)(text ? text : ""); *p; p++)
        dm_str_catn(s, (*p < 0x20 && *p != '\n' && *p != '\t') || *p == 0x7f ? "?"
                           : (const char *)p, 1);
}

const char *dm_term_safe(const char *text, char **buf)
{
    *buf = NULL;
    if (!text)
        return "";
    for (const unsigned char *p = (const unsigned char *)text; *p; p++)
        if ((*p < 0x20 && *p != '\n' && *p != '\t') || *p == 0x7f) {
            dm_str t = {0};
            dm_str_cat_term(&t, text);
            *buf = dm_str_take(&t);
            return *buf;
        }
    return text;
}

void *dm_vec_push(void *arr, size_t *n, const void *elem, size_t size)
{
    void **p = arr;
    *p = dm_xrealloc(*p, (*n + 1) * size);
    char *e = (char *)*p + *n * size;
    if (elem)
        memcpy(e, elem, size);
    else
        memset(e, 0, size);
    (*n)++;
    return e;
}
