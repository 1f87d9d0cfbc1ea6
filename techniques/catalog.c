/* catalog.c — the one registry of techniques and sweep axes (catalog.h). */
#include "techniques/catalog.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "techniques/maps.h"
#include "techniques/mesh.h"
#include "techniques/shaders.h"
#include "techniques/user_technique_internal.h"

extern const technique_desc technique__list[];
extern const size_t technique__list_count;

#define CATALOG__MAX_TECHNIQUES 64
#define CATALOG__MAX_AXES 64
#define CATALOG__MAX_USER_AXES (USER_TECHNIQUE_MAX * USER_TECHNIQUE_MAX_PARAMS)

/* The user techniques and the axes of their parameters, in load order;
 * loading and reloading hold catalog__lock. */
static user_technique__tech catalog__users[USER_TECHNIQUE_MAX];
static size_t catalog__n_users;
static const axis_info *catalog__user_axes[CATALOG__MAX_USER_AXES];
static size_t catalog__n_user_axes;
static pthread_mutex_t catalog__lock = PTHREAD_MUTEX_INITIALIZER;

/* The names a user may choose (the technique axis's choices point here). */
static const char *catalog__names[CATALOG__MAX_TECHNIQUES + 1];
static pthread_once_t catalog__names_once = PTHREAD_ONCE_INIT;

/* The built-in axis rows with the registries' choices filled in, and
 * their indices in the order of their names (axes_find's binary search:
 * planning asks for an axis by name for every axis of every combination). */
static axis_info catalog__axes[CATALOG__MAX_AXES];
static size_t catalog__n_axes;
static unsigned char catalog__by_name[CATALOG__MAX_AXES];
static pthread_once_t catalog__axes_once = PTHREAD_ONCE_INIT;

/* ---- techniques ------------------------------------------------------------ */

size_t technique_count(void) { return technique__list_count + catalog__n_users; }

const technique_desc *technique_at(size_t i)
{
    return i < technique__list_count ? &technique__list[i] : user_technique_at(i - technique__list_count);
}

const technique_desc *technique_find(const char *name)
{
    for (size_t i = 0; name && i < technique_count(); i++)
        if (strcmp(technique_at(i)->name, name) == 0)
            return technique_at(i);
    return NULL;
}

static void catalog__init_names(void)
{
    size_t n = 0;
    for (size_t i = 0; i < technique_count() && n < CATALOG__MAX_TECHNIQUES; i++)
        if (!technique_at(i)->test_only)
            catalog__names[n++] = technique_at(i)->name;
    catalog__names[n] = NULL;
}

const char *const *technique_names(void)
{
    pthread_once(&catalog__names_once, catalog__init_names);
    return catalog__names;
}

int technique_reads_axis(const technique_desc *t, const char *name)
{
    const axis_info *a = axes_find(name);
    if (!t || !a)
        return 0;
    if (a->scene)
        return 1;
    for (size_t i = 0; t->axes && t->axes[i]; i++)
        if (strcmp(t->axes[i], name) == 0)
            return 1;
    return 0;
}

/* ---- axes ------------------------------------------------------------------ */

/* The technique row: a technique's name, or a user's file, loaded (and
 * registered) here so that a sweep naming it fails at plan time. */
static int catalog__check_technique(const axis_info *a, const char *value, dm_str *err)
{
    if (user_technique_is_path(value))
        return user_technique_load(value, NULL, err);
    return axes_kind_check(a, value, err);
}

static void catalog__init_axes(void)
{
    const axis_info *rows = axes_builtin(&catalog__n_axes);
    memcpy(catalog__axes, rows, catalog__n_axes * sizeof *rows);
    catalog__axes[0].choices = technique_names();
    catalog__axes[0].check = catalog__check_technique;
    catalog__axes[1].choices = mesh_names();
    catalog__axes[catalog__n_axes - 1].choices = maps_names();
    for (size_t i = 0; i < catalog__n_axes; i++) {   /* insertion sort by name */
        size_t j = i;
        for (; j > 0 && strcmp(catalog__axes[catalog__by_name[j - 1]].name, catalog__axes[i].name) > 0; j--)
            catalog__by_name[j] = catalog__by_name[j - 1];
        catalog__by_name[j] = (unsigned char)i;
    }
}

size_t axes_count(void)
{
    pthread_once(&catalog__axes_once, catalog__init_axes);
    return catalog__n_axes + catalog__n_user_axes;
}

const axis_info *axes_at(size_t i)
{
    pthread_once(&catalog__axes_once, catalog__init_axes);
    return i < catalog__n_axes ? &catalog__axes[i] : user_technique_axis_at(i - catalog__n_axes);
}

const axis_info *axes_find(const char *name)
{
    if (!name)
        return NULL;
    pthread_once(&catalog__axes_once, catalog__init_axes);
    size_t lo = 0, hi = catalog__n_axes;   /* the built-in rows, by name */
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        const axis_info *a = &catalog__axes[catalog__by_name[mid]];
        int c = strcmp(a->name, name);
        if (c == 0)
            return a;
        if (c < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    for (size_t i = 0; i < catalog__n_user_axes; i++)   /* then the users' parameters */
        if (strcmp(catalog__user_axes[i]->name, name) == 0)
            return catalog__user_axes[i];
    return NULL;
}

/* "unknown axis 'x'; did you mean ...? valid axes: ..." (built-in names). */
static int catalog__unknown_axis(const char *name, dm_str *err)
{
    const char *names[CATALOG__MAX_AXES];
    size_t n = 0;
    for (; n < catalog__n_axes; n++)
        names[n] = axes_at(n)->name;
    dm_str_printf(err, "unknown axis '%s'", name);
    dm_str_suggest(err, name, names, n, "axes");
    return DM_ERR_UNKNOWN;
}

int axes_check(const char *name, const char *value, dm_str *err)
{
    const axis_info *a = axes_find(name);
    if (!a)
        return catalog__unknown_axis(name ? name : "", err);
    return axes_value_check(a, value ? value : "", err);
}

char *axes_canonical(const char *name, const char *value)
{
    dm_str scratch = {0};
    int rc = axes_check(name, value, &scratch);
    dm_str_free(&scratch);
    if (rc)
        return NULL;
    const axis_info *a = axes_find(name);
    char *canon = axes_value_canonical(a, value);
    if (canon)
        return canon;
    if (a->kind == AXIS_ENUM && user_technique_by_path(value))
        return dm_xstrdup(user_technique_by_path(value)->name);   /* a user file: its name */
    return dm_xstrdup(value);
}

int axes_condition_holds(const char *name, const char *(*value)(const char *axis, void *ctx),
                         void *ctx)
{
    return axes_find(name) ? axes_conditions_hold(name, value, ctx) : 0;
}

/* ---- user techniques ------------------------------------------------------- */

size_t user_technique_count(void) { return catalog__n_users; }

const technique_desc *user_technique_at(size_t i)
{
    return i < catalog__n_users ? &catalog__users[i].desc : NULL;
}

size_t user_technique_axis_count(void) { return catalog__n_user_axes; }

const axis_info *user_technique_axis_at(size_t i)
{
    return i < catalog__n_user_axes ? catalog__user_axes[i] : NULL;
}

static user_technique__tech *catalog__user_of(const technique_desc *t)
{
    for (size_t i = 0; t && i < catalog__n_users; i++)
        if (&catalog__users[i].desc == t)
            return &catalog__users[i];
    return NULL;
}

const char *user_technique_path(const technique_desc *t)
{
    user_technique__tech *u = catalog__user_of(t);
    return u ? u->path : NULL;
}

const technique_desc *user_technique_by_path(const char *path)
{
    for (size_t i = 0; path && i < catalog__n_users; i++)
        if (strcmp(catalog__users[i].path, path) == 0)
            return &catalog__users[i].desc;
    return NULL;
}

const char *user_technique_shader_source(const char *name)
{
    for (size_t i = 0; name && i < catalog__n_users; i++)
        if (strcmp(catalog__users[i].stage, name) == 0)
            return catalog__users[i].shader;
    return NULL;
}

void user_technique_map_log(const technique_desc *t, const char *log, dm_str *out)
{
    user_technique__map_log(user_technique_path(t), log, out);
}

/* The parser's question (user_technique__taken_fn): which axis holds name, if any. */
static const char *catalog__taken(const char *name, void *ctx)
{
    (void)ctx;
    const axis_info *a = axes_find(name);
    for (size_t i = 0; a && i < catalog__n_user_axes; i++)
        if (catalog__user_axes[i] == a)
            return "user parameter";
    return a ? "built-in" : NULL;
}

/* Publishes t (parsed and filled) into the registry: its parameters become
 * axes, its name a choice of the technique axis, its stage a shader source. */
static void catalog__register(user_technique__tech *t)
{
    for (size_t i = 0; i < t->n_params; i++)
        catalog__user_axes[catalog__n_user_axes++] = &t->params[i].axis;
    shaders_add(t->stage, t->shader);
    catalog__n_users++;
    pthread_once(&catalog__names_once, catalog__init_names);
    catalog__init_names();
}

static int catalog__load_locked(const char *path, const char **name, dm_str *err)
{
    char *text = NULL;
    int rc = user_technique__read(path, &text, err);
    if (rc)
        return rc;
    for (size_t i = 0; i < catalog__n_users; i++)
        if (strcmp(catalog__users[i].path, path) == 0 && strcmp(catalog__users[i].text, text) == 0) {
            free(text);
            if (name)
                *name = catalog__users[i].name;
            return 0;   /* the same file again (a sweep parsed twice) */
        }
    if (catalog__n_users == USER_TECHNIQUE_MAX) {
        free(text);
        dm_str_printf(err, "%s: more than %d user techniques in one run", path, USER_TECHNIQUE_MAX);
        return DM_ERR_RANGE;
    }
    user_technique__tech *t = &catalog__users[catalog__n_users];
    memset(t, 0, sizeof *t);
    user_technique__parse p = {.path = path, .err = err, .t = t, .taken = catalog__taken};
    rc = user_technique__header(&p, text);
    p.line = t->name_line;
    if (rc == 0 && technique_find(t->name))
        rc = user_technique__fail(&p, "technique name '%s' is taken (by %s); choose another in "
                                      "`//@technique`",
                      t->name, user_technique_path(technique_find(t->name))
                                   ? user_technique_path(technique_find(t->name)) : "a built-in technique");
    rc = rc ? rc : user_technique__entry(&p, text);
    if (rc) {
        free(text);
        memset(t, 0, sizeof *t);
        return rc;
    }
    t->path = dm_xstrdup(path);
    t->text = text;
    user_technique__fill(t);
    catalog__register(t);
    if (name)
        *name = t->name;
    return 0;
}

int user_technique_load(const char *path, const char **name, dm_str *err)
{
    pthread_mutex_lock(&catalog__lock);
    int rc = catalog__load_locked(path, name, err);
    pthread_mutex_unlock(&catalog__lock);
    return rc;
}

/* Re-reads t's file: 1 when its text changed and was taken, 0 when it did
 * not change, a DM_ERR_* with a line in msg when it was refused. */
static int catalog__reload_one(user_technique__tech *t, dm_str *msg)
{
    char *text = NULL;
    dm_str err = {0};
    int rc = user_technique__read(t->path, &text, &err);
    if (rc == 0 && strcmp(text, t->text) == 0) {
        free(text);
        return 0;
    }
    user_technique__tech *fresh = dm_xcalloc(1, sizeof *fresh);
    user_technique__parse p = {.path = t->path, .err = &err, .t = fresh, .self = t, .taken = catalog__taken};
    rc = rc ? rc : user_technique__header(&p, text);
    rc = rc ? rc : user_technique__entry(&p, text);
    if (rc == 0 && (strcmp(fresh->name, t->name) != 0 || fresh->base != t->base || fresh->color != t->color ||
                    !user_technique__same_params(fresh, t)))
        rc = user_technique__fail(&p, "its name, base, functions or parameters changed; restart to use them");
    if (rc == 0) {
        free(t->text);
        char *old = t->shader;
        t->text = text;
        t->shader = user_technique__compose(t);
        shaders_add(t->stage, t->shader);
        free(old);
        t->desc.source_hash = dm_fnv1a64(text, strlen(text), DM_FNV_SEED);
    } else {
        dm_str_printf(msg, "%s\n", dm_str_get(&err));
        free(text);
    }
    free(fresh);
    dm_str_free(&err);
    return rc ? rc : 1;
}

int user_technique_reload(dm_str *msg)
{
    pthread_mutex_lock(&catalog__lock);
    int changed = 0;
    for (size_t i = 0; i < catalog__n_users; i++)
        changed += catalog__reload_one(&catalog__users[i], msg) == 1;
    pthread_mutex_unlock(&catalog__lock);
    return changed;
}

int user_technique_check_text(const char *path, const char *text, dm_str *err)
{
    pthread_mutex_lock(&catalog__lock);
    user_technique__tech *t = dm_xcalloc(1, sizeof *t);
    user_technique__parse p = {.path = path, .err = err, .t = t, .taken = catalog__taken};
    int rc = user_technique__header(&p, text);
    rc = rc ? rc : user_technique__entry(&p, text);
    free(t);
    pthread_mutex_unlock(&catalog__lock);
    return rc;
}
