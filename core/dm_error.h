/* dm_error.h — the one list of error codes used by every dmbench module.
 *
 * Functions return 0 on success or a negative code from DM_ERRORS.  Each code
 * has a name (dm_errname) and a short message (dm_strerror).  A message for a
 * user is built by the caller and names the file, line, value and the valid
 * choices; the code only says what kind of failure it was.
 */
#ifndef CORE_DM_ERROR_H
#define CORE_DM_ERROR_H

#define DM_ERRORS(X)                                                        \
    X(OK,          0,   "success")                                          \
    X(NOMEM,       -1,  "out of memory")                                    \
    X(IO,          -2,  "input/output error")                               \
    X(PARSE,       -3,  "malformed input")                                  \
    X(ARG,         -4,  "invalid argument")                                 \
    X(UNKNOWN,     -5,  "unknown name")                                     \
    X(UNSUPPORTED, -6,  "not supported by this driver")                     \
    X(GL,          -7,  "OpenGL error")                                     \
    X(SHADER,      -8,  "shader compile or link failure")                   \
    X(NOTFOUND,    -9,  "not found")                                        \
    X(MISUSE,      -10, "API used out of order")                            \
    X(UNAVAILABLE, -11, "value unavailable")                                \
    X(NUMERIC,     -12, "numerical failure")                                \
    X(TIMEOUT,     -13, "timed out")                                        \
    X(CHILD,       -14, "child process failed")                             \
    X(STORE,       -15, "results store error")                              \
    X(RANGE,       -16, "value out of range")                               \
    X(EXISTS,      -17, "already exists")                                 \
    X(BUSY,        -18, "in use by another process")                        \
    X(DISK,        -19, "the disk refused the write (full, quota or file-size limit)")

enum dm_error {
#define DM__ENUM(name, code, msg) DM_ERR_##name = (code),
    DM_ERRORS(DM__ENUM)
#undef DM__ENUM
};

/* Name of a code ("DM_ERR_PARSE"), or "DM_ERR_?" for an unknown code. */
const char *dm_errname(int code);
/* Short human message of a code ("malformed input"). */
const char *dm_strerror(int code);

#endif
