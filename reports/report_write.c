/* report_write.c — the four files of a report as rows of one table, and
 * the folder they go into (report.h: report_write_all and its variants).
 * The writers (report_json.c, report_csv.c, report_md.c, report_html.c)
 * read the run and the shared helpers of report.c; only this file calls
 * them, so the writers and their helpers form no circle. */
#include "reports/report.h"
#include "reports/report_internal.h"
#include "reports/published_report.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"

/* One file of a report: its name in the folder and its writer (dir: the
 * run directory the images are relative to; t: trend lines or NULL). */
typedef struct report_write__file {
    const char *name;
    int (*write)(const dm_run_result *run, const char *dir, const char *path, const report_trends *t);
} report_write__file;

static int report_write__json(const dm_run_result *run, const char *dir, const char *path,
                              const report_trends *t)
{
    (void)dir, (void)t;
    return report_write_json(run, path);
}

static int report_write__csv(const dm_run_result *run, const char *dir, const char *path,
                             const report_trends *t)
{
    (void)dir, (void)t;
    return report_write_csv(run, path);
}

static int report_write__md(const dm_run_result *run, const char *dir, const char *path,
                            const report_trends *t)
{
    (void)dir, (void)t;
    return report_write_markdown(run, path);
}

static int report_write__html(const dm_run_result *run, const char *dir, const char *path,
                              const report_trends *t)
{
    return report_write_html_trends(run, dir, path, "", t);
}

/* In the order they are written; a new kind of file is one more row. */
static const report_write__file report_write__files[] = {
    {"results.json", report_write__json},
    {"results.csv", report_write__csv},
    {"summary.md", report_write__md},
    {"report.html", report_write__html},
};

/* Writes the four files; stops at the first failure and names that file. */
int report_write_all_to(const dm_run_result *run, const char *dir, const char *out, char *err,
                        size_t errlen)
{
    return report_write_all_trends(run, dir, out, NULL, err, errlen);
}


/* Copies every image the run names (safe relative paths that exist) from
 * dir to the same relative path under out, so out is self-contained.  0,
 * or DM_ERR_IO with err naming the file. */
static int report_write__copy_images(const dm_run_result *run, const char *dir, const char *out, char *err,
                               size_t errlen)
{
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        const char *imgs[] = {c->img_reference, c->img_render, c->img_heatmap, c->img_flip};
        for (size_t k = 0; k < sizeof imgs / sizeof *imgs; k++) {
            if (!imgs[k] || !report__safe_relpath(imgs[k]))
                continue;
            char *from = dm_xasprintf("%s/%s", dir, imgs[k]), *to = dm_xasprintf("%s/%s", out, imgs[k]);
            int rc = dm_file_exists(from) && !dm_file_exists(to)
                         ? report__copy_file(from, to, err, errlen) : 0;
            free(from);
            free(to);
            if (rc)
                return rc;
        }
    }
    return 0;
}

int report_write_all_trends(const dm_run_result *run, const char *dir, const char *out,
                            const report_trends *t, char *err, size_t errlen)
{
    if (!run || !dir || !out) {
        snprintf(err, errlen, "report_write_all: no run or no directory");
        return DM_ERR_ARG;
    }
    /* written elsewhere: the images come along, so the folder stands alone */
    int rc = report_published_copy(dir, out, err, errlen);   /* summary.md reads it beside itself */
    if (!rc && strcmp(dir, out) != 0)
        rc = report_write__copy_images(run, dir, out, err, errlen);
    for (size_t i = 0; i < sizeof report_write__files / sizeof *report_write__files && !rc; i++) {
        const report_write__file *w = &report_write__files[i];
        char *path = dm_xasprintf("%s/%s", out, w->name);
        rc = w->write(run, dir, path, t);
        if (rc)   /* errno of the failed write (dm_write_file) */
            snprintf(err, errlen, "%s: cannot write: %s", path,
                     rc == DM_ERR_DISK || rc == DM_ERR_IO ? strerror(errno) : dm_strerror(rc));
        free(path);
    }
    return rc;
}

int report_write_all(const dm_run_result *run, const char *dir, char *err, size_t errlen)
{
    return report_write_all_to(run, dir, dir, err, errlen);
}
