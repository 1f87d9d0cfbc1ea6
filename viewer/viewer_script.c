/* viewer_script.c — parsing `--keys` scripts (see viewer_script.h). */
#include "viewer/viewer_script.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/dm_error.h"

#define VIEWER__MAX_WAIT 100000

static void viewer__push(viewer_event **ev, size_t *n, viewer_event e)
{
    DM_VEC_PUSH(*ev, *n, e);
}

/* One {name} or {name:args} token (without braces); 0 or DM_ERR_PARSE. */
static int viewer__named(const char *tok, viewer_event **ev, size_t *n)
{
    static const struct { const char *name; unsigned ch; } chars[] = {
        {"space", ' '}, {"dot", '.'}, {"lbrace", '{'}};
    for (size_t i = 0; i < sizeof chars / sizeof *chars; i++)
        if (strcasecmp(tok, chars[i].name) == 0) {
            viewer__push(ev, n, (viewer_event){.kind = VIEWER_EV_CHAR, .ch = chars[i].ch});
            return 0;
        }
    if (strcasecmp(tok, "esc") == 0) {
        viewer__push(ev, n, (viewer_event){.kind = VIEWER_EV_ESC});
        return 0;
    }
    int k = 0, end = 0;
    double a = 0, b = 0;
    if (sscanf(tok, "wait:%d%n", &k, &end) == 1 && tok[end] == '\0' && k >= 0 && k <= VIEWER__MAX_WAIT) {
        for (int i = 0; i < k; i++)
            viewer__push(ev, n, (viewer_event){.kind = VIEWER_EV_WAIT});
        return 0;
    }
    if (sscanf(tok, "drag:%lf,%lf%n", &a, &b, &end) == 2 && tok[end] == '\0') {
        viewer__push(ev, n, (viewer_event){.kind = VIEWER_EV_DRAG, .dx = a, .dy = b});
        return 0;
    }
    if (sscanf(tok, "pan:%lf,%lf%n", &a, &b, &end) == 2 && tok[end] == '\0') {
        viewer__push(ev, n, (viewer_event){.kind = VIEWER_EV_PAN, .dx = a, .dy = b});
        return 0;
    }
    if (sscanf(tok, "wheel:%lf%n", &a, &end) == 1 && tok[end] == '\0') {
        viewer__push(ev, n, (viewer_event){.kind = VIEWER_EV_WHEEL, .dy = a});
        return 0;
    }
    return DM_ERR_PARSE;
}

int viewer_script_parse(const char *script, viewer_event **out, size_t *n, dm_str *err)
{
    viewer_event *ev = NULL;
    size_t count = 0;
    for (const char *p = script; *p; p++) {
        if (isspace((unsigned char)*p))
            continue;
        if (*p == '.') {
            viewer__push(&ev, &count, (viewer_event){.kind = VIEWER_EV_WAIT});
            continue;
        }
        if (*p != '{') {
            viewer__push(&ev, &count, (viewer_event){.kind = VIEWER_EV_CHAR, .ch = (unsigned char)*p});
            continue;
        }
        const char *close = strchr(p, '}');
        char tok[64] = "";
        size_t len = close ? (size_t)(close - p - 1) : 0;
        if (close && len < sizeof tok)
            memcpy(tok, p + 1, len);
        tok[len < sizeof tok ? len : 0] = '\0';
        if (!close || len >= sizeof tok || viewer__named(tok, &ev, &count) != 0) {
            dm_str_printf(err, "--keys: bad event at offset %zu ('%.20s'); valid: a character, '.', "
                          "{wait:N}, {esc}, {drag:DX,DY}, {pan:DX,DY}, {wheel:N}, {space}, {dot}, "
                          "{lbrace}",
                          (size_t)(p - script), p);
            free(ev);
            return DM_ERR_PARSE;
        }
        p = close;
    }
    *out = ev;
    *n = count;
    return 0;
}
