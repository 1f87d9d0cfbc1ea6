/* report_write.c — the files of a report as rows of one table, and the
 * folder they go into (report.h: report_write, report_write_run).
 * The writers (report_json.c, report_csv.c, report_md.c, report_html.c)
 * read the report model (report_model.h); only this file calls them, so
 * the writers, the model and their helpers form no circle. */
#include "reports/report.h"
#include "reports/report_internal.h"
#include "reports/published_report.h"
#include "reports/answer.h"
#include "reports/report_model.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"

/* One file of a report: its name in the folder and its writer, which reads
 * only the model (and the desc for where the images are linked). */
typedef struct report_write__file {
    const char *name;
    int (*write)(const report_model *m, const report_desc *d, const char *path);
} report_write__file;

/* In the order they are written; a new kind of file is one more row. */
static const report_write__file report_write__files[] = {
    {"results.json", report__write_json},
    {"results.csv", report__write_csv},
    {"summary.md", report__write_md},
    {"report.html", report__write_html},
    {"front.tex", report__write_tex},
};
#define REPORT_WRITE__N (sizeof report_write__files / sizeof *report_write__files)

/* Copies image rel (skipped when NULL, unsafe, missing or already there)
 * from dir to the same relative path under out.  0, or DM_ERR_IO with err
 * naming the file. */
static int report_write__copy_one(const char *rel, const char *dir, const char *out, char *err,
                                  size_t errlen)
{
    if (!rel || !report__safe_relpath(rel))
        return 0;
    char *from = dm_xasprintf("%s/%s", dir, rel), *to = dm_xasprintf("%s/%s", out, rel);
    int rc = dm_file_exists(from) && !dm_file_exists(to) ? report__copy_file(from, to, err, errlen) : 0;
    free(from);
    free(to);
    return rc;
}

/* Copies every image the run names (safe relative paths that exist) from
 * dir to the same relative path under out, so out is self-contained: the
 * still images, and along a path the temporal error map and the
 * filmstrip's frames.  0, or DM_ERR_IO with err naming the file. */
static int report_write__copy_images(const dm_run_result *run, const char *dir, const char *out, char *err,
                               size_t errlen)
{
    int rc = 0;
    for (size_t i = 0; i < run->n_configs && !rc; i++) {
        const dm_config_result *c = &run->configs[i];
        const dm_path_quality *q = &c->path_quality;
        const char *imgs[] = {c->img_reference, c->img_render, c->img_heatmap, c->img_flip, q->img_temporal};
        for (size_t k = 0; k < sizeof imgs / sizeof *imgs && !rc; k++)
            rc = report_write__copy_one(imgs[k], dir, out, err, errlen);
        for (size_t k = 0; k < q->n_shots && !rc; k++) {
            rc = report_write__copy_one(q->shots[k].img_test, dir, out, err, errlen);
            if (!rc)
                rc = report_write__copy_one(q->shots[k].img_ref, dir, out, err, errlen);
            if (!rc)
                rc = report_write__copy_one(q->shots[k].img_flip, dir, out, err, errlen);
        }
    }
    return rc;
}

/* Writes one row of the table to path; err names the file when it fails. */
static int report_write__one(const report_model *m, const report_desc *d, const report_write__file *w,
                             const char *path, char *err, size_t errlen)
{
    int rc = w->write(m, d, path);
    if (rc)   /* errno of the failed write (dm_write_file) */
        snprintf(err, errlen, "%s: cannot write: %s", path,
                 rc == DM_ERR_DISK || rc == DM_ERR_IO ? strerror(errno) : dm_strerror(rc));
    return rc;
}

/* One file of the table by name (d->file), to d->path or out/name. */
static int report_write__file_named(const report_model *m, const report_desc *d, const char *out,
                                    char *err, size_t errlen)
{
    for (size_t i = 0; i < REPORT_WRITE__N; i++) {
        const report_write__file *w = &report_write__files[i];
        if (strcmp(w->name, d->file) != 0)
            continue;
        char *path = d->path ? dm_xstrdup(d->path) : dm_xasprintf("%s/%s", out ? out : ".", w->name);
        int rc = report_write__one(m, d, w, path, err, errlen);
        free(path);
        return rc;
    }
    dm_str rows = {0};
    for (size_t i = 0; i < REPORT_WRITE__N; i++)
        dm_str_printf(&rows, "%s%s", i ? ", " : "", report_write__files[i].name);
    snprintf(err, errlen, "report_write: no file '%s' (valid: %s)", d->file, dm_str_get(&rows));
    dm_str_free(&rows);
    return DM_ERR_ARG;
}

int report_write(const report_model *m, const report_desc *d, char *err, size_t errlen)
{
    const char *out = d && d->out ? d->out : d ? d->dir : NULL;
    if (!m || !m->run || !d || (!out && !(d->file && d->path))) {
        snprintf(err, errlen, "report_write: no run or no directory");
        return DM_ERR_ARG;
    }
    if (d->file)
        return report_write__file_named(m, d, out, err, errlen);
    /* written elsewhere: the images come along, so the folder stands alone */
    int rc = d->dir ? report_published_copy(d->dir, out, err, errlen) : 0;
    if (!rc && d->dir && strcmp(d->dir, out) != 0)
        rc = report_write__copy_images(m->run, d->dir, out, err, errlen);
    for (size_t i = 0; i < REPORT_WRITE__N && !rc; i++) {
        char *path = dm_xasprintf("%s/%s", out, report_write__files[i].name);
        rc = report_write__one(m, d, &report_write__files[i], path, err, errlen);
        free(path);
    }
    return rc;
}

int report_write_run(const dm_run_result *run, const report_desc *d, char *err, size_t errlen)
{
    report_model m;
    int rc = report_model_build(&m, run, d);
    if (rc) {
        snprintf(err, errlen, "report_write: no run");
        return rc;
    }
    rc = report_write(&m, d, err, errlen);
    report_model_free(&m);
    return rc;
}

/* The terminal's answer is one more reader of the model: built here, as
 * for the files, so answer.c calls nothing that derives it. */
void report_answer_terminal(const dm_run_result *run, dm_str *out)
{
    report_model m;
    if (report_model_build(&m, run, NULL) == 0)
        report_answer_terminal_model(&m, out);
    report_model_free(&m);
}
