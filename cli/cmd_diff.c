/* cmd_diff.c — `dmbench diff REF TEST`: every image metric of two image
 * files (any format OpenImageIO reads), and optionally the FLIP map. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "core/dm_util.h"
#include "imaging/flip.h"
#include "imaging/image.h"
#include "imaging/quality.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct diff_args {
    const char *map;           /* -o / --heatmap: the FLIP map, the report's heatmap */
    double ppd;
    int json;
} diff_args;

const cli_option cli_diff_options[] = {
    { .name = "heatmap", .short_name = 'o', .kind = CLI_OPT_STRING, .offset = offsetof(diff_args, map),
      .value_name = "MAP.png", .help = "write the heatmap, the report's: " FLIP_SCALE_TEXT " (docs/flip.md), to MAP.png "
      "[default: beside TEST, its name with .flip.png]" },
    { .name = "ppd", .kind = CLI_OPT_DOUBLE, .offset = offsetof(diff_args, ppd), .value_name = "N",
      .def = "67.0206", .min = 1, .max = 600,
      .help = "pixels per degree FLIP assumes (FLIP's: 0.7 m from a 0.7 m wide 3840-pixel monitor)" },
    CLI_BOOL("json", diff_args, json, "print JSON"),
    CLI_OPT_END
};

/* Bins of the FLIP histogram: [0, 0.1), [0.1, 0.2), ... [0.9, 1]. */
#define DIFF__BINS 10

typedef struct diff__result {
    img_metrics m;
    double ssim, silhouette;
    int opaque;                /* both images opaque everywhere: no silhouette */
    flip_stats flip;
    size_t hist[DIFF__BINS];   /* FLIP values per bin */
    size_t n;                  /* pixels */
    long nonfinite_ref, nonfinite_test;
} diff__result;

/* 1 when every alpha of im is 1: no alpha channel (img_load gives 1) or a
 * fully opaque one, so its coverage is the whole image. */
static int diff__opaque(const img *im)
{
    for (size_t i = 3; i < (size_t)im->w * im->h * 4; i += 4)
        if (im->px[i] != 1.0f)
            return 0;
    return 1;
}

/* Counts the n FLIP values of map into DIFF__BINS bins of width 0.1 (1
 * itself in the last). */
static void diff__histogram(const float *map, size_t n, size_t *hist)
{
    for (size_t b = 0; b < DIFF__BINS; b++)
        hist[b] = 0;
    for (size_t i = 0; i < n; i++) {
        double v = map[i] < 0 ? 0 : map[i];
        size_t b = (size_t)(v * DIFF__BINS);
        hist[b < DIFF__BINS ? b : DIFF__BINS - 1]++;
    }
}

/* Replaces NaN/Inf values of im by 0 (alpha by 1) and returns how many
 * pixels had one: they are reported, not carried into every metric. */
static long diff__sanitise(img *im)
{
    long bad = quality_nonfinite_pixels(im);
    for (size_t i = 0; bad && i < (size_t)im->w * im->h * 4; i++)
        if (!isfinite(im->px[i]))
            im->px[i] = i % 4 == 3 ? 1.0f : 0.0f;
    return bad;
}

/* All metrics of test against ref (same size); map gets the FLIP map. */
static int diff__compute(img *ref, img *test, double ppd, float *map, diff__result *r)
{
    r->nonfinite_ref = diff__sanitise(ref);
    r->nonfinite_test = diff__sanitise(test);
    size_t n = (size_t)ref->w * ref->h;
    unsigned char *ma = malloc(n), *mb = malloc(n);
    int rc = ma && mb ? 0 : DM_ERR_NOMEM;
    rc = rc ? rc : img_compare(ref, test, 0.05, &r->m);
    rc = rc ? rc : quality_ssim(ref, test, &r->ssim);
    rc = rc ? rc : flip_compare(ref, test, &(flip_desc){ .ppd = ppd }, &r->flip, map);
    if (rc == 0) {
        quality_coverage(ref, ma);
        quality_coverage(test, mb);
        r->opaque = diff__opaque(ref) && diff__opaque(test);
        r->silhouette = r->opaque ? NAN : quality_silhouette_error(ma, mb, n);
        r->n = n;
        diff__histogram(map, n, r->hist);
    }
    free(ma);
    free(mb);
    return rc;
}

#define DIFF__OPAQUE_WHY "both images are opaque everywhere (no alpha channel, or alpha 1): " \
                         "coverage is the whole image in both, so 1 - IoU would be 0 by construction"

static void diff__print_json(const char *a, const char *b, const img *im, double ppd,
                             const diff__result *r, const char *map_path)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "reference", a);
    cJSON_AddStringToObject(o, "test", b);
    cJSON_AddNumberToObject(o, "width", im->w);
    cJSON_AddNumberToObject(o, "height", im->h);
    cJSON_AddNumberToObject(o, "RMSE", r->m.rmse);
    cJSON_AddNumberToObject(o, "PSNR", r->m.psnr);         /* +inf → null */
    cJSON_AddBoolToObject(o, "PSNR_infinite", isinf(r->m.psnr) && r->m.psnr > 0);
    cJSON_AddNumberToObject(o, "SSIM", r->ssim);
    cJSON_AddNumberToObject(o, "MaxError", r->m.max_error);
    cJSON_AddNumberToObject(o, "PctOverThreshold", r->m.pct_over);
    if (r->opaque)
        cJSON_AddStringToObject(o, "SilhouetteErrorLeftOut", DIFF__OPAQUE_WHY);
    else
        cJSON_AddNumberToObject(o, "SilhouetteError", r->silhouette);
    cJSON_AddNumberToObject(o, "FLIP", r->flip.mean);
    cJSON_AddNumberToObject(o, "FLIPQ1", r->flip.q1);
    cJSON_AddNumberToObject(o, "FLIPMedian", r->flip.median);
    cJSON_AddNumberToObject(o, "FLIPQ3", r->flip.q3);
    cJSON_AddNumberToObject(o, "FLIPMax", r->flip.max);
    cJSON_AddNumberToObject(o, "FLIPPixelsPerDegree", ppd);
    cJSON *h = cJSON_AddArrayToObject(o, "FLIPHistogram");   /* pixels per 0.1-wide bin */
    for (size_t b = 0; b < DIFF__BINS; b++)
        cJSON_AddItemToArray(h, cJSON_CreateNumber((double)r->hist[b]));
    cJSON_AddStringToObject(o, "FLIPMap", map_path ? map_path : "");
    cJSON_AddNumberToObject(o, "NonFinitePixelsReference", (double)r->nonfinite_ref);
    cJSON_AddNumberToObject(o, "NonFinitePixels", (double)r->nonfinite_test);
    char *text = cJSON_Print(o);
    puts(text);
    free(text);
    cJSON_Delete(o);
}

static void diff__print_text(const char *a, const char *b, const img *im, double ppd,
                             const diff__result *r, const char *map_path)
{
    char *ba = NULL, *bb = NULL;   /* paths as typed: control bytes shown as '?' */
    printf("%s vs %s (%dx%d)\n", dm_term_safe(a, &ba), dm_term_safe(b, &bb), im->w, im->h);
    free(ba);
    free(bb);
    printf("  RMSE        %.6g\n", r->m.rmse);
    if (isinf(r->m.psnr))
        printf("  PSNR        inf dB (identical)\n");
    else
        printf("  PSNR        %.2f dB\n", r->m.psnr);
    printf("  SSIM        %.6f\n", r->ssim);
    printf("  MaxError    %.6g  (%.3g %% of pixels over 0.05)\n", r->m.max_error, r->m.pct_over);
    if (r->opaque)
        printf("  silhouette  left out: %s\n", DIFF__OPAQUE_WHY);
    else
        printf("  silhouette  %.6g  (1 - IoU of alpha coverage)\n", r->silhouette);
    printf("  FLIP        mean %.6f, max %.6f, at %.4g pixels per degree\n", r->flip.mean,
           r->flip.max, ppd);
    printf("              weighted quartiles (by error, as FLIP pools them): Q1 %.4f, median "
           "%.4f, Q3 %.4f\n", r->flip.q1, r->flip.median, r->flip.q3);
    printf("  FLIP histogram (pixels per bin of 0.1; # = share of the pixels, 40 columns = all):\n");
    for (size_t b = 0; b < DIFF__BINS; b++) {
        double share = r->n ? (double)r->hist[b] / (double)r->n : 0;
        int bar = (int)lround(share * 40);
        printf("    [%.1f, %.1f%s %9zu %6.2f %%  %.*s\n", (double)b / DIFF__BINS,
               (double)(b + 1) / DIFF__BINS, b + 1 == DIFF__BINS ? "]" : ")", r->hist[b],
               share * 100, bar, "########################################");
    }
    if (map_path) {
        char *bm = NULL;
        printf("  map         %s (FLIP per pixel, fixed scale 0..1, docs/flip.md)\n",
               dm_term_safe(map_path, &bm));
        free(bm);
    }
}

/* The map's path when -o is not given: TEST's path with its extension
 * replaced by ".flip.png" ("out/b.pfm" -> "out/b.flip.png"); caller frees. */
static char *diff__default_map(const char *test)
{
    const char *slash = strrchr(test, '/'), *dot = strrchr(test, '.');
    size_t stem = dot && (!slash || dot > slash + 1) ? (size_t)(dot - test) : strlen(test);
    return dm_xasprintf("%.*s.flip.png", (int)stem, test);
}

/* Loads path into im; prints the reason and returns the exit code when it
 * cannot: 2 for what the user named (missing, not a regular file, not an
 * image), 4 when the machine could not hold its pixels (DM_ERR_NOMEM). */
static int diff__load(const char *path, img *im)
{
    char err[512];
    int e = img_load(path, im, err, sizeof err);
    return e == 0 ? 0 : cli_error(e, "diff: cannot read %s", err);
}

/* `dmbench diff REF TEST [-o MAP.png] [--ppd N] [--json]`: exit 0; 2 for
 * bad input: a file that cannot be read as an image, images of different
 * sizes (both named), a map path that cannot be written (with the reason);
 * 4 for the machine: images too large for the memory it may use, a disk
 * that refuses the map (full, ulimit -f), which is never left half written.
 * Paths reach the terminal with their control bytes as '?'. */
int cli_diff(const cli_command *self, int argc, char **argv)
{
    diff_args a = {0};
    int rc = cli_parse(self, argc, argv, &a, &argc);
    if (rc >= 0)
        return rc;
    if (argc != 2)
        return cli_usage_error("diff: expected two images, REF and TEST (got %d argument%s)", argc,
                               argc == 1 ? "" : "s");
    img ref = {0}, test = {0};
    float *map = NULL;
    diff__result r = {0};
    rc = diff__load(argv[0], &ref);
    rc = rc ? rc : diff__load(argv[1], &test);
    if (rc == 0 && (ref.w != test.w || ref.h != test.h))
        rc = cli_usage_error("diff: the images differ in size: '%s' is %dx%d, '%s' is %dx%d", argv[0],
                             ref.w, ref.h, argv[1], test.w, test.h);
    if (rc == 0) {
        map = malloc((size_t)ref.w * (size_t)ref.h * sizeof *map);
        int e = map ? diff__compute(&ref, &test, a.ppd, map, &r) : DM_ERR_NOMEM;
        char why[160];
        if (e == DM_ERR_NOMEM)
            rc = cli_error(e, "diff: %s", dm_nomem_reason(why, sizeof why));
        else if (e != 0) {
            cli_error(e, "diff: %s", dm_strerror(e));
            rc = (int)dm_exit_from_error(e);
        }
    }
    if (rc == 0 && (r.nonfinite_ref || r.nonfinite_test)) {
        char *ba = NULL, *bb = NULL;
        fprintf(stderr, "dmbench: warning: diff: non-finite (NaN/Inf) pixels: %ld in '%s', %ld in '%s'; "
                        "they count as 0 in every metric\n", r.nonfinite_ref, dm_term_safe(argv[0], &ba),
                r.nonfinite_test, dm_term_safe(argv[1], &bb));
        free(ba);
        free(bb);
    }
    char err[512];
    char *path = rc == 0 ? (a.map ? dm_xstrdup(a.map) : diff__default_map(argv[1])) : NULL;
    int e = path ? flip_map_save(map, ref.w, ref.h, path, err, sizeof err) : 0;
    if (e && a.map) {
        rc = cli_error(e, "diff: cannot write the map %s", err);
    } else if (e) {   /* the default place refused it: the figures still stand */
        char *bp = NULL;
        fprintf(stderr, "dmbench: warning: diff: the FLIP map was not written (%s); name a "
                        "place with -o MAP.png\n", dm_term_safe(err, &bp));
        free(bp);
        free(path);
        path = NULL;
    }
    if (rc == 0 && a.json)
        diff__print_json(argv[0], argv[1], &ref, a.ppd, &r, path);
    else if (rc == 0)
        diff__print_text(argv[0], argv[1], &ref, a.ppd, &r, path);
    free(path);
    free(map);
    img_free(&ref);
    img_free(&test);
    return rc;
}
