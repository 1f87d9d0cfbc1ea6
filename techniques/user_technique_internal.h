/* user_technique_internal.h — a user technique file as a value, shared by
 * the parser (user_technique.c) and the catalog that registers it
 * (catalog.c).  Nothing else includes it.
 *
 * The parser reads a file into a user_technique__tech and checks it; it registers
 * nothing and reads no registry: whether a parameter's name is taken is a
 * question it asks through user_technique__parse.taken, which the catalog answers.
 * Usage (catalog.c):
 *     user_technique__tech t = {0};
 *     user_technique__parse p = {.path = path, .err = err, .t = &t, .taken = ..., .taken_ctx = ...};
 *     rc = user_technique__read(path, &text, err);
 *     rc = rc ? rc : user_technique__header(&p, text);    // name, base, parameters
 *     ... the catalog checks the name is free ...
 *     rc = rc ? rc : user_technique__entry(&p, text);     // the entry point(s)
 *     t.path = ..., t.text = text; user_technique__fill(&t);   // desc, axes, composed stage
 */
#ifndef TECHNIQUES_USER_TECHNIQUE_INTERNAL_H
#define TECHNIQUES_USER_TECHNIQUE_INTERNAL_H

#include "techniques/user_technique.h"

/* Most built-in axes a base reads. */
#define USER_TECHNIQUE__MAX_BUILTIN 16

/* What a user file can be (`//@base`): the built-in stage its code is
 * appended to, the entry point it must define and the define that calls it. */
typedef struct user_technique__base {
    const char *name, *stage_file, *entry, *entry_types, *returns, *defines;
    const char *const *axes;
    const char *const *program;  /* the built-in stages of its program (their u_ names are taken) */
} user_technique__base;

/* One `//@param`: a sweep axis NAME and the uniform u_NAME. */
typedef struct user_technique__param {
    char name[64];
    axis_kind kind;
    double min, max;
    char def[32];
    char help[160];
    int line;                    /* of its `//@param` */
    axis_info axis;              /* the axis it becomes (user_technique__fill) */
} user_technique__param;

/* A parsed user technique file; after user_technique__fill, desc is its descriptor. */
typedef struct user_technique__tech {
    technique_desc desc;
    char name[64], summary[200], stage[80];   /* stage: "user:NAME", the composed stage */
    char defines[128];           /* the base's, + USER_COLOR when it defines user_color */
    int color;                   /* defines vec4 user_color(vec2 uv, vec3 v, vec3 at) */
    char *path, *text, *shader;
    const user_technique__base *base;        /* `//@base`, default fragment */
    const char *axes[USER_TECHNIQUE__MAX_BUILTIN + USER_TECHNIQUE_MAX_PARAMS + 1];
    user_technique__param params[USER_TECHNIQUE_MAX_PARAMS];
    size_t n_params;
    int name_line;               /* line of `//@technique` */
} user_technique__tech;

/* What is taken by an axis called name: "built-in", "user parameter", or
 * NULL when the name is free. */
typedef const char *(*user_technique__taken_fn)(const char *name, void *ctx);

/* One parse: where messages go and what the parse fills. */
typedef struct user_technique__parse {
    const char *path;
    int line;                    /* of the message; 0: none */
    dm_str *err;
    user_technique__tech *t;
    const user_technique__tech *self;        /* reloading: the registered technique of this file */
    user_technique__taken_fn taken;          /* NULL: every name is free */
    void *taken_ctx;
} user_technique__parse;

/* Appends "path:line: message" (or "path: message" when p->line is 0) to
 * p->err; returns DM_ERR_PARSE. */
int user_technique__fail(user_technique__parse *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Reads the file at path into *text (malloc'd).  0, or DM_ERR_IO (missing,
 * unreadable, not a regular file) / DM_ERR_PARSE (a NUL byte) with
 * "path: ..." in err. */
int user_technique__read(const char *path, char **text, dm_str *err);
/* The `//@` header of text into p->t: name, summary, base and parameters
 * (each checked, against p->taken too).  0 or DM_ERR_PARSE. */
int user_technique__header(user_technique__parse *p, const char *text);
/* The entry point(s) of text for p->t's base.  0 or DM_ERR_PARSE. */
int user_technique__entry(user_technique__parse *p, const char *text);
/* The composed stage of t (malloc'd): its base's stage, the parameters'
 * uniforms, the user's file from line USER_TECHNIQUE_LINE_BASE + 1. */
char *user_technique__compose(const user_technique__tech *t);
/* Fills t's descriptor, axis list, parameter axes, stage name and composed
 * stage from a parsed t with path and text set. */
void user_technique__fill(user_technique__tech *t);
/* 1 when a and b declare the same parameters (names, kinds, ranges, defaults). */
int user_technique__same_params(const user_technique__tech *a, const user_technique__tech *b);
/* user_technique_map_log for the file at path (NULL: a built-in technique). */
void user_technique__map_log(const char *path, const char *log, dm_str *out);

#endif
