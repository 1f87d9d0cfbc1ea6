/* dm_util.h — small shared utilities: logging, strings, clocks, hashing, files.
 *
 * Everything here is layer-neutral (no GL, no SQLite, no libraries) so that
 * every folder may depend on core/ without breaking the one-way flow of
 * README, Layout.
 */
#ifndef CORE_DM_UTIL_H
#define CORE_DM_UTIL_H

#include <stddef.h>
#include <stdio.h>
#include <stdint.h>
#include <stdarg.h>

/* ---- logging ---------------------------------------------------------- */
enum dm_log_level { DM_LOG_ERROR = 0, DM_LOG_WARN, DM_LOG_INFO, DM_LOG_DEBUG };
void dm_log_set_level(enum dm_log_level level);
enum dm_log_level dm_log_get_level(void);
/* Prints "dmbench: <level>: message\n" on stderr when level is enabled. */
void dm_log(enum dm_log_level level, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* ---- growable arrays --------------------------------------------------
 * The one convention for arrays that grow: a pointer and a count side by
 * side, appended to with dm_vec_push (one realloc per element; the arrays
 * here hold tens of elements, not millions). */
/* Appends the `size` bytes at elem (zeroes when elem is NULL) to the array
 * *(T **)arr of *n elements; returns the new element. */
void *dm_vec_push(void *arr, size_t *n, const void *elem, size_t size);
/* arr[n++] = v, growing arr (both lvalues, evaluated more than once). */
#define DM_VEC_PUSH(arr, n, v)                                                  \
    do {                                                                         \
        dm_vec_push(&(arr), &(n), NULL, sizeof *(arr));                          \
        (arr)[(n) - 1] = (v);                                                    \
    } while (0)

/* ---- growable string -------------------------------------------------- */
typedef struct dm_str { char *buf; size_t len, cap; } dm_str;
/* Appends; on allocation failure aborts (strings are small; see dm_xmalloc). */
void dm_str_cat(dm_str *s, const char *text);
void dm_str_catn(dm_str *s, const char *text, size_t n);
void dm_str_printf(dm_str *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void dm_str_vprintf(dm_str *s, const char *fmt, va_list ap);
/* Appends text with & < > " ' escaped for HTML. */
void dm_str_cat_html(dm_str *s, const char *text);
/* Appends text for one Markdown table cell or heading that a renderer such
 * as GitHub's shows as plain text: '|' escaped, '<' '>' '&' as entities
 * (no raw HTML from a sweep name or a path), '`' as '\'', line breaks as
 * spaces, other control bytes (ANSI escapes) as '?'. */
void dm_str_cat_md(dm_str *s, const char *text);
/* Appends text for a terminal: control bytes other than '\n' and '\t'
 * (ESC of ANSI sequences, '\r', ...) as '?', so user text cannot move the
 * cursor, recolour or retitle the terminal. */
void dm_str_cat_term(dm_str *s, const char *text);
/* text if it has no control bytes, else a sanitised copy in *buf (freed by
 * the caller, NULL when not needed); for printing user text to a terminal. */
const char *dm_term_safe(const char *text, char **buf);
/* Returns the buffer ("" when empty); the dm_str keeps ownership. */
const char *dm_str_get(const dm_str *s);
/* Hands the buffer to the caller (never NULL) and resets s. */
char *dm_str_take(dm_str *s);
void dm_str_free(dm_str *s);

/* ---- suggestions ------------------------------------------------------ */
/* The choice closest to word by case-insensitive edit distance, or NULL when none is within
 * max(2, strlen(word)/3) edits (so "did you mean" is only said when likely). */
const char *dm_closest(const char *word, const char *const *choices, size_t n);
/* Appends "a, b, c" (n choices) to s. */
void dm_str_cat_list(dm_str *s, const char *const *choices, size_t n);
/* The one "did you mean": after "unknown <thing> 'word'" appends
 * "; did you mean 'X'? valid <what>: a, b, c" (X from dm_closest), or
 * "; valid <what>: a, b, c" when no choice is close. */
void dm_str_suggest(dm_str *s, const char *word, const char *const *choices, size_t n,
                    const char *what);
/* The same for a value that must be one of a fixed set: appends
 * "expected one of: a, b, c" and " (did you mean 'X'?)" when one is close. */
void dm_str_expected(dm_str *s, const char *value, const char *const *choices, size_t n);

/* ---- memory: abort with a message on failure (for small bookkeeping) --- */
void *dm_xmalloc(size_t n);
void *dm_xcalloc(size_t count, size_t n);
void *dm_xrealloc(void *p, size_t n);
char *dm_xstrdup(const char *s);          /* NULL in, NULL out */
char *dm_xasprintf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* ---- clocks ------------------------------------------------------------ */
int64_t dm_now_ns(void);          /* CLOCK_MONOTONIC */
int64_t dm_cpu_ns(void);          /* CLOCK_PROCESS_CPUTIME_ID */
int64_t dm_thread_cpu_ns(void);   /* CLOCK_THREAD_CPUTIME_ID */
/* ISO-8601 UTC timestamp of now, "2026-11-21T23:04:24Z", into buf[32]. */
void dm_iso8601_now(char buf[32]);

/* ---- hashing ----------------------------------------------------------- */
uint64_t dm_fnv1a64(const void *data, size_t n, uint64_t seed);
#define DM_FNV_SEED 0xcbf29ce484222325ULL
/* 16 lowercase hex digits of h into out[17]. */
void dm_hex64(uint64_t h, char out[17]);

/* ---- lists of paths ---------------------------------------------------- */
/* Splits list, comma-separated paths (`--from A,B`, `compare A1,A2 B1,B2`),
 * into *items (*n of them, each malloc'd; dm_strv_free frees them).  A list
 * that names an existing file or directory as a whole is one path, commas
 * and all, so a run directory with a comma in its name can be given.  An
 * empty list or an empty entry ("", ",", "a,,b") is DM_ERR_ARG with err
 * naming the list ("what" says whose it is); *items is then NULL, *n 0. */
int dm_split_paths(const char *list, const char *what, char ***items, size_t *n, dm_str *err);
void dm_strv_free(char **v, size_t n);

/* ---- files ------------------------------------------------------------- */
/* Reads a whole file; returns 0 and a NUL-terminated malloc'd buffer, or a
 * negative DM_ERR_* (DM_ERR_IO) and *out untouched. */
int dm_read_file(const char *path, char **out, size_t *len);
/* Appends all that is left to read from f (a file or a pipe) to out; returns
 * 0, or DM_ERR_IO on a read error with what was read before it in out. */
int dm_read_stream(FILE *f, dm_str *out);
/* Writes atomically: a temp file beside path, then rename; on failure the
 * temp file is removed and the old file (if any) is left as it was.
 * Returns 0, DM_ERR_DISK when the disk refused the write (dm_disk_errno),
 * or DM_ERR_IO (no such directory, permission, ...); errno says why. */
int dm_write_file(const char *path, const void *data, size_t len);
/* 1 for the errno values of a disk that refused a write: full (ENOSPC),
 * over quota (EDQUOT), past a file-size limit (EFBIG: ulimit -f) or failing
 * (EIO).  Such a failure is the machine's (exit 4), not the input's. */
int dm_disk_errno(int e);
/* mkdir -p; 0 if it exists or was made. */
int dm_mkdirs(const char *path);
int dm_file_exists(const char *path);
/* The one check every input file passes before it is opened (sweep files,
 * maps, meshes, user GLSL, images for `diff`, results files, CSV tables):
 * 0 when path names a regular file (after symlinks).  Else, without opening
 * it, DM_ERR_NOTFOUND (no such file), DM_ERR_ARG (a directory, FIFO, socket
 * or device: reading /dev/zero or a pipe never ends) or DM_ERR_IO (stat
 * failed otherwise: permission, a name too long), with the reason ("not a
 * regular file (a directory, FIFO or device)", or strerror) in why when
 * why is not NULL. */
int dm_input_file(const char *path, char *why, size_t whylen);
/* Why a large allocation failed, into buf (returned): "out of memory under
 * the address-space limit of N MB (ulimit -v K)" when such a limit is set,
 * else "out of memory"; for the message of a DM_ERR_NOMEM (exit 4). */
const char *dm_nomem_reason(char *buf, size_t len);

#endif
