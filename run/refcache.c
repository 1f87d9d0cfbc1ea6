/* refcache.c — on-disk cache of quality reference images (see refcache.h). */
#include "refcache.h"
#include "core/dm_error.h"
#include "techniques/axes.h"
#include "techniques/maps.h"
#include "techniques/shaders.h"
#include "techniques/technique.h"

#include <dirent.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define REFCACHE__MAGIC "DMREF001"

char *refcache_dir(void)
{
    /* maps_cache_dir() decides the cache root (DMBENCH_CACHE_DIR, XDG,
     * HOME); the references live beside the maps. */
    char *maps = maps_cache_dir();
    char *slash = strrchr(maps, '/');
    if (slash)
        *slash = '\0';
    char *dir = dm_xasprintf("%s/references", maps);
    free(maps);
    return dir;
}

static int refcache__cmp_kv(const void *a, const void *b)
{
    const dm_kv *x = *(const dm_kv *const *)a, *y = *(const dm_kv *const *)b;
    return strcmp(x->key, y->key);
}

/* Hash of the composed text of every stage of t: a shader edit changes the
 * key even when the technique's version was not bumped. */
static int refcache__sources(const technique_desc *t, uint64_t *hash)
{
    const char *stages[5] = {t->vs, t->tcs, t->tes, t->gs, t->fs};
    dm_str src = {0}, err = {0};
    int rc = 0;
    *hash = DM_FNV_SEED;
    for (int i = 0; rc == 0 && i < 5; i++) {
        if (!stages[i])
            continue;
        dm_str_free(&src);
        rc = shaders_compose(stages[i], t->defines, &src, &err);
        if (rc == 0)
            *hash = dm_fnv1a64(src.buf, src.len, *hash);
    }
    dm_str_free(&src);
    dm_str_free(&err);
    return rc;
}

/* Appends "name=value" lines: every axis t reads, in catalog order, valued
 * as the renderer sees it (canonical text, the axis default when params
 * leave it out); then every parameter that is no axis, sorted.  Axes t does
 * not read cannot change its image (the planner folds on the same rule), so
 * a scene's reference matches whichever configuration asks for it first. */
static void refcache__params(const technique_desc *t, const dm_kv *p, size_t n, dm_str *key)
{
    for (size_t i = 0; i < axes_count(); i++) {
        const axis_info *a = axes_at(i);
        /* which frames get a reference, not what one looks like: the frame
         * line says which, and still keys stay as they were */
        if (!technique_reads_axis(t, a->name) || strcmp(a->name, "camera.path_ref_every") == 0)
            continue;
        const char *v = dm_kv_get(p, n, a->name);
        char *canon = v ? axes_canonical(a->name, v) : NULL;
        dm_str_printf(key, "%s=%s\n", a->name, canon ? canon : v ? v : a->def ? a->def : "");
        free(canon);
    }
    const dm_kv **other = dm_xcalloc(n + 1, sizeof *other);
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (!axes_find(p[i].key))
            other[k++] = &p[i];
    qsort(other, k, sizeof *other, refcache__cmp_kv);
    for (size_t i = 0; i < k; i++)
        dm_str_printf(key, "%s=%s\n", other[i]->key, other[i]->value ? other[i]->value : "");
    free(other);
}

int refcache_key(const refcache_desc *desc, dm_str *key)
{
    const char *name = dm_kv_get(desc->params, desc->n_params, "technique");
    if (!name || desc->width < 1 || desc->height < 1)
        return DM_ERR_ARG;
    const technique_desc *t = technique_find(name);
    if (!t)
        return DM_ERR_UNKNOWN;
    uint64_t sources;
    int rc = refcache__sources(t, &sources);
    if (rc != 0)
        return rc;
    char hex[17];
    dm_hex64(sources, hex);
    dm_str_free(key);
    struct stat st;
    if (stat("/proc/self/exe", &st) != 0)
        memset(&st, 0, sizeof st);
    dm_str_printf(key, "technique %s version %d sources %s\nsize %dx%d supersample %d\ndriver %s\n"
                  "binary %lld bytes modified %lld.%09ld\n", t->name, t->version, hex, desc->width,
                  desc->height, desc->supersample > 1 ? desc->supersample : 1,
                  desc->driver ? desc->driver : "", (long long)st.st_size, (long long)st.st_mtim.tv_sec,
                  st.st_mtim.tv_nsec);
    if (desc->on_path)
        dm_str_printf(key, "frame %llu\n", desc->frame);
    refcache__params(t, desc->params, desc->n_params, key);
    return 0;
}

static char *refcache__path(const char *dir, const char *key)
{
    char hex[17];
    dm_hex64(dm_fnv1a64(key, strlen(key), DM_FNV_SEED), hex);
    return dm_xasprintf("%s/%s.dmref", dir, hex);
}

int refcache_load(const char *dir, const char *key, int w, int h, float **rgba, float **depth)
{
    char *path = refcache__path(dir, key), *buf = NULL;
    size_t len = 0;
    int rc = dm_read_file(path, &buf, &len);
    free(path);
    if (rc != 0)
        return DM_ERR_NOTFOUND;
    uint32_t klen = 0;
    int32_t fw = 0, fh = 0;
    size_t np = (size_t)w * (size_t)h, head = 8 + sizeof klen;
    if (len >= head)
        memcpy(&klen, buf + 8, sizeof klen);
    if (len < head || memcmp(buf, REFCACHE__MAGIC, 8) != 0 || klen != strlen(key) ||
        len < head + klen + 2 * sizeof fw || memcmp(buf + head, key, klen) != 0) {
        free(buf);
        return DM_ERR_NOTFOUND;
    }
    const char *p = buf + head + klen;
    memcpy(&fw, p, sizeof fw);
    memcpy(&fh, p + sizeof fw, sizeof fh);
    p += 2 * sizeof fw;
    rc = fw != w || fh != h ? DM_ERR_NOTFOUND
         : (size_t)(buf + len - p) != np * 5 * sizeof(float) ? DM_ERR_IO : 0;
    if (rc == 0) {
        char *used = refcache__path(dir, key);
        utimensat(AT_FDCWD, used, NULL, 0);   /* least recently used goes first */
        free(used);
        *rgba = dm_xmalloc(np * 4 * sizeof **rgba);
        memcpy(*rgba, p, np * 4 * sizeof **rgba);
        if (depth) {
            *depth = dm_xmalloc(np * sizeof **depth);
            memcpy(*depth, p + np * 4 * sizeof(float), np * sizeof **depth);
        }
    }
    free(buf);
    return rc;
}

int refcache_store(const char *dir, const char *key, int w, int h, const float *rgba,
                   const float *depth)
{
    if (w < 1 || h < 1 || !rgba || !depth || dm_mkdirs(dir) != 0)
        return DM_ERR_IO;
    uint32_t klen = (uint32_t)strlen(key);
    int32_t dims[2] = {w, h};
    size_t np = (size_t)w * (size_t)h;
    size_t len = 8 + sizeof klen + klen + sizeof dims + np * 5 * sizeof(float);
    char *buf = dm_xmalloc(len), *p = buf;
    memcpy(p, REFCACHE__MAGIC, 8);
    memcpy(p += 8, &klen, sizeof klen);
    memcpy(p += sizeof klen, key, klen);
    memcpy(p += klen, dims, sizeof dims);
    memcpy(p += sizeof dims, rgba, np * 4 * sizeof(float));
    memcpy(p + np * 4 * sizeof(float), depth, np * sizeof(float));
    char *path = refcache__path(dir, key);
    int rc = dm_write_file(path, buf, len) == 0 ? 0 : DM_ERR_IO;
    free(path);
    free(buf);
    if (rc == 0)
        refcache_trim(dir, REFCACHE_MAX_BYTES);
    return rc;
}

typedef struct refcache__entry { char *path; off_t size; struct timespec used; } refcache__entry;

static int refcache__older(const void *a, const void *b)
{
    const refcache__entry *x = a, *y = b;
    if (x->used.tv_sec != y->used.tv_sec)
        return x->used.tv_sec < y->used.tv_sec ? -1 : 1;
    return (x->used.tv_nsec > y->used.tv_nsec) - (x->used.tv_nsec < y->used.tv_nsec);
}

int refcache_trim(const char *dir, unsigned long long max_bytes)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    refcache__entry *e = NULL;
    size_t n = 0;
    unsigned long long total = 0;
    struct stat st;
    for (struct dirent *de; (de = readdir(d));) {
        size_t len = strlen(de->d_name);
        char *path = dm_xasprintf("%s/%s", dir, de->d_name);
        if (len > 6 && strcmp(de->d_name + len - 6, ".dmref") == 0 && stat(path, &st) == 0) {
            refcache__entry en = {path, st.st_size, st.st_mtim};
            DM_VEC_PUSH(e, n, en);
            total += (unsigned long long)st.st_size;
        } else {
            free(path);
        }
    }
    closedir(d);
    qsort(e, n, sizeof *e, refcache__older);
    int removed = 0;
    for (size_t i = 0; i < n; i++) {
        if (total > max_bytes && unlink(e[i].path) == 0) {
            total -= (unsigned long long)e[i].size;
            removed++;
        }
        free(e[i].path);
    }
    free(e);
    return removed;
}
