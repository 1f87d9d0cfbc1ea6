/* inputs.c — the user's map and mesh files a run reads, held to one version
 * (see inputs.h). */
#include "run/inputs.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "techniques/maps.h"
#include "techniques/user_mesh.h"

typedef struct inputs__file {
    char *path;
    const char *kind;        /* "mesh" or "map": for messages */
    uint64_t hash;           /* FNV-1a of the bytes when registered */
    struct stat st;          /* the stat that goes with hash */
} inputs__file;

static pthread_mutex_t inputs__lock = PTHREAD_MUTEX_INITIALIZER;
static inputs__file *inputs__files;
static size_t inputs__n;

/* Same file, same size, same modification and change times. */
static int inputs__same_stat(const struct stat *a, const struct stat *b)
{
    return a->st_dev == b->st_dev && a->st_ino == b->st_ino && a->st_size == b->st_size &&
           a->st_mtim.tv_sec == b->st_mtim.tv_sec && a->st_mtim.tv_nsec == b->st_mtim.tv_nsec &&
           a->st_ctim.tv_sec == b->st_ctim.tv_sec && a->st_ctim.tv_nsec == b->st_ctim.tv_nsec;
}

/* Hashes the file's bytes and stats it (the stat taken before reading, so a
 * write during the read shows as a changed stat at the next check).
 * Returns 0, or DM_ERR_ARG with why. */
static int inputs__hash_file(const char *path, uint64_t *hash, struct stat *st, char *why, size_t whylen)
{
    if (dm_input_file(path, why, whylen) != 0)   /* never open a FIFO or a device */
        return DM_ERR_ARG;
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0 || fstat(fd, st) != 0) {
        snprintf(why, whylen, "%s", strerror(errno));
        if (fd >= 0)
            close(fd);
        return DM_ERR_ARG;
    }
    size_t cap = 1 << 20;
    unsigned char *buf = dm_xmalloc(cap);
    uint64_t h = DM_FNV_SEED;
    ssize_t got;
    while ((got = read(fd, buf, cap)) > 0)
        h = dm_fnv1a64(buf, (size_t)got, h);
    if (got < 0)
        snprintf(why, whylen, "%s", strerror(errno));
    free(buf);
    close(fd);
    *hash = h;
    return got < 0 ? DM_ERR_ARG : 0;
}

/* Registers one file (kept once); the caller holds the lock. */
static int inputs__add(const char *path, const char *kind, dm_str *err)
{
    for (size_t i = 0; i < inputs__n; i++)
        if (strcmp(inputs__files[i].path, path) == 0)
            return 0;
    inputs__file f = {.kind = kind};
    char why[256] = "";
    if (inputs__hash_file(path, &f.hash, &f.st, why, sizeof why) != 0) {
        dm_str_printf(err, "%s: the %s file cannot be read: %s", path, kind, why);
        return DM_ERR_ARG;
    }
    f.path = dm_xstrdup(path);
    inputs__files = dm_xrealloc(inputs__files, (inputs__n + 1) * sizeof *inputs__files);
    inputs__files[inputs__n++] = f;
    return 0;
}

/* Registers the files one parameter value names: a user mesh, or the maps
 * of a material. */
static int inputs__value(const char *key, const char *value, dm_str *err)
{
    size_t np = strlen(USER_MESH_PREFIX);
    if (strcmp(key, "mesh") == 0 && strncmp(value, USER_MESH_PREFIX, np) == 0)
        return inputs__add(value + np, "mesh", err);
    if (strcmp(key, "maps") != 0 || !maps_is_material(value))
        return 0;
    char *paths[3];
    int rc = maps_material_paths(value, paths, err);
    for (int k = 0; k < 3 && !rc; k++)
        if (paths[k])
            rc = inputs__add(paths[k], "map", err);
    for (int k = 0; k < 3; k++)
        free(paths[k]);
    return rc;
}

int inputs_collect(const plan *p, dm_str *err)
{
    int rc = 0;
    pthread_mutex_lock(&inputs__lock);
    for (size_t c = 0; rc == 0 && c < p->n_configs; c++) {
        const plan_config *pc = &p->configs[c];
        for (size_t i = 0; rc == 0 && i < pc->n_params; i++)
            rc = inputs__value(pc->params[i].key, pc->params[i].value, err);
        for (size_t i = 0; rc == 0 && i < pc->n_scene_params; i++)
            rc = inputs__value(pc->scene_params[i].key, pc->scene_params[i].value, err);
    }
    pthread_mutex_unlock(&inputs__lock);
    return rc;
}

size_t inputs_count(void) { return inputs__n; }
const char *inputs_path(size_t i) { return i < inputs__n ? inputs__files[i].path : NULL; }
uint64_t inputs_hash(size_t i) { return i < inputs__n ? inputs__files[i].hash : 0; }

int inputs_check(dm_str *err)
{
    int rc = 0;
    pthread_mutex_lock(&inputs__lock);
    for (size_t i = 0; rc == 0 && i < inputs__n; i++) {
        inputs__file *f = &inputs__files[i];
        struct stat st;
        if (stat(f->path, &st) == 0 && inputs__same_stat(&st, &f->st))
            continue;
        uint64_t now = 0;
        char why[256] = "", was[17], is[17];
        dm_hex64(f->hash, was);
        if (inputs__hash_file(f->path, &now, &st, why, sizeof why) != 0) {
            dm_str_printf(err, "%s: the %s file cannot be read since the run started (%s)", f->path,
                          f->kind, why);
            rc = DM_ERR_ARG;
        } else if (now != f->hash) {
            dm_hex64(now, is);
            dm_str_printf(err, "%s: the %s file changed since the run started (hash %s, now %s)",
                          f->path, f->kind, was, is);
            rc = DM_ERR_ARG;
        } else {
            f->st = st;   /* touched, same bytes: the new stat goes with the hash */
        }
    }
    pthread_mutex_unlock(&inputs__lock);
    return rc;
}

int inputs_resume_check(const dm_kv *env, size_t n_env, const char *run_id, dm_str *err)
{
    size_t np = strlen(INPUTS_ENV_PREFIX);
    for (size_t k = 0; k < n_env; k++) {
        if (strncmp(env[k].key, INPUTS_ENV_PREFIX, np) != 0)
            continue;
        const char *path = env[k].key + np;
        uint64_t now = 0;
        struct stat st;
        char why[256] = "", is[17];
        if (inputs__hash_file(path, &now, &st, why, sizeof why) != 0) {
            dm_str_printf(err, "--resume: %s: a file run %s measured cannot be read now (%s); "
                          "restore it to resume, or run without --resume to start a new run",
                          path, run_id, why);
            return DM_ERR_ARG;
        }
        dm_hex64(now, is);
        if (strcmp(env[k].value, is) != 0) {
            dm_str_printf(err, "--resume: %s: the file changed since run %s measured it (hash %s, "
                          "now %s); one run measures one version of each file: restore it to "
                          "resume, or run without --resume to start a new run",
                          path, run_id, env[k].value, is);
            return DM_ERR_ARG;
        }
    }
    return 0;
}

void inputs_record(dm_kv **env, size_t *n_env)
{
    pthread_mutex_lock(&inputs__lock);
    for (size_t i = 0; i < inputs__n; i++) {
        char hash[17];
        dm_hex64(inputs__files[i].hash, hash);
        char *key = dm_xasprintf("%s%s", INPUTS_ENV_PREFIX, inputs__files[i].path);
        dm_kv_push(env, n_env, key, hash);
        free(key);
    }
    pthread_mutex_unlock(&inputs__lock);
}

void inputs_clear(void)
{
    pthread_mutex_lock(&inputs__lock);
    for (size_t i = 0; i < inputs__n; i++)
        free(inputs__files[i].path);
    free(inputs__files);
    inputs__files = NULL;
    inputs__n = 0;
    pthread_mutex_unlock(&inputs__lock);
}
