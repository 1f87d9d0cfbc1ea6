/* drivers.c — driver selection by DMBENCH_DRIVER (see drivers.h). */
#include "run/drivers.h"
#include "core/dm_error.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const driver_info drivers__table[] = {
    {"default", "what EGL gives: the system's Mesa (llvmpipe on a machine without a GPU)", 0, NULL},
    {"llvmpipe", "llvmpipe of the system's Mesa (Debian 12: 22.3), forced with GALLIUM_DRIVER", 0, "llvmpipe"},
    {"llvmpipe-25", "llvmpipe of Mesa 25 from bookworm-backports (scripts/install-mesa25)", 1, "llvmpipe"},
    {"zink", "zink (GL over Vulkan) on lavapipe, Mesa 25 (scripts/install-mesa25)", 1, "zink"},
    {NULL, NULL, 0, NULL},
};

/* Set by drivers_enter in the process it re-executes: "NAME:PID", the
 * driver applied and the pid of the process that applied it (execv keeps
 * the pid).  It holds in that process and in its children; anywhere else
 * (a user's shell that exported it, a process started by a child) it is
 * stale, and drivers_enter removes it. */
#define DRIVERS__APPLIED "DMBENCH_DRIVER_APPLIED"

const driver_info *drivers_list(void) { return drivers__table; }

const driver_info *drivers_find(const char *name)
{
    for (const driver_info *d = drivers__table; name && d->name; d++)
        if (strcmp(d->name, name) == 0)
            return d;
    return NULL;
}

const char *drivers_mesa25_prefix(void)
{
    const char *p = getenv("DMBENCH_MESA25_PREFIX");
    return p && *p ? p : "/opt/dmbench/mesa-25";
}

static char *drivers__lib(void)
{
    return dm_xasprintf("%s/usr/lib/x86_64-linux-gnu", drivers_mesa25_prefix());
}

const char *drivers_missing(const driver_info *d, char **why_buf)
{
    *why_buf = NULL;
    if (!d->mesa25)
        return NULL;
    char *lib = drivers__lib();
    const char *need[] = {"libEGL_mesa.so.0", "dri/swrast_dri.so", "libvulkan_lvp.so", NULL};
    for (size_t i = 0; need[i]; i++) {
        if (i == 2 && strcmp(d->name, "zink") != 0)
            break;
        char *f = dm_xasprintf("%s/%s", lib, need[i]);
        struct stat st;
        int ok = stat(f, &st) == 0;
        if (!ok)
            *why_buf = dm_xasprintf("driver '%s' needs Mesa 25 in %s, and %s is missing "
                                    "(run scripts/install-mesa25, or set DMBENCH_MESA25_PREFIX)",
                                    d->name, drivers_mesa25_prefix(), f);
        free(f);
        if (!ok)
            break;
    }
    free(lib);
    return *why_buf;
}

/* The driver name of the marker (static; "" when there is none), once
 * drivers_enter has kept or removed it. */
static char drivers__applied[64];

/* Reads the marker: its name into drivers__applied when it was set by this
 * process or its parent, else removes it from the environment. */
static void drivers__read_marker(void)
{
    const char *a = getenv(DRIVERS__APPLIED);
    const char *colon = a ? strrchr(a, ':') : NULL;
    char *end = NULL;
    long pid = colon ? strtol(colon + 1, &end, 10) : 0;
    size_t len = colon ? (size_t)(colon - a) : 0;
    drivers__applied[0] = '\0';
    if (colon && end && !*end && (pid == (long)getpid() || pid == (long)getppid()) && len > 0 &&
        len < sizeof drivers__applied)
        snprintf(drivers__applied, sizeof drivers__applied, "%.*s", (int)len, a);
    else if (a)
        unsetenv(DRIVERS__APPLIED);   /* inherited from outside: not this process tree's driver */
}

const char *drivers_current(void)
{
    const char *d = getenv("DMBENCH_DRIVER");
    return drivers__applied[0] ? drivers__applied : d && *d ? d : "default";
}

/* prepends dir to the colon-separated variable name */
static void drivers__prepend(const char *name, const char *dir)
{
    const char *old = getenv(name);
    char *v = old && *old ? dm_xasprintf("%s:%s", dir, old) : dm_xstrdup(dir);
    setenv(name, v, 1);
    free(v);
}

int drivers_enter(char **argv, dm_str *err)
{
    drivers__read_marker();
    const char *name = getenv("DMBENCH_DRIVER");
    if (!name || !*name || strcmp(name, "default") == 0)
        return 0;
    const driver_info *d = drivers_find(name);
    if (!d) {
        dm_str_printf(err, "DMBENCH_DRIVER=%s: unknown driver; the drivers are:", name);
        for (const driver_info *k = drivers__table; k->name; k++) {
            char *why = NULL;
            dm_str_printf(err, " %s%s", k->name, drivers_missing(k, &why) ? " (not installed)" : "");
            free(why);
        }
        return DM_ERR_ARG;
    }
    if (strcmp(drivers__applied, name) == 0)
        return 0;
    char *why = NULL;
    if (drivers_missing(d, &why)) {
        dm_str_printf(err, "%s", why);
        free(why);
        return DM_ERR_UNSUPPORTED;
    }
    if (d->gallium)
        setenv("GALLIUM_DRIVER", d->gallium, 1);
    if (d->mesa25) {
        char *lib = drivers__lib();
        char *dri = dm_xasprintf("%s/dri", lib), *gbm = dm_xasprintf("%s/gbm", lib);
        char *egl = dm_xasprintf("%s/usr/share/glvnd/egl_vendor.d/50_mesa.json", drivers_mesa25_prefix());
        drivers__prepend("LD_LIBRARY_PATH", lib);
        setenv("LIBGL_DRIVERS_PATH", dri, 1);
        setenv("GBM_BACKENDS_PATH", gbm, 1);
        setenv("__EGL_VENDOR_LIBRARY_FILENAMES", egl, 1);
        free(lib);
        free(dri);
        free(gbm);
        free(egl);
    }
    if (strcmp(d->name, "zink") == 0) {
        /* Without lavapipe's ICD the Vulkan loader finds no device and zink
         * hangs at start-up.  The loader takes VK_DRIVER_FILES before
         * VK_ICD_FILENAMES and lets the other variables add or filter out
         * drivers, so all of them are set or removed: the driver named
         * zink is zink on this lavapipe, whatever the user's shell says. */
        char *icd = dm_xasprintf("%s/lvp_icd.json", drivers_mesa25_prefix());
        setenv("VK_DRIVER_FILES", icd, 1);
        setenv("VK_ICD_FILENAMES", icd, 1);
        unsetenv("VK_ADD_DRIVER_FILES");
        unsetenv("VK_LOADER_DRIVERS_SELECT");
        unsetenv("VK_LOADER_DRIVERS_DISABLE");
        setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
        free(icd);
    }
    char *marker = dm_xasprintf("%s:%ld", name, (long)getpid());
    setenv(DRIVERS__APPLIED, marker, 1);
    free(marker);
    fflush(NULL);
    execv("/proc/self/exe", argv);
    dm_str_printf(err, "DMBENCH_DRIVER=%s: cannot re-execute dmbench: %s", name, strerror(errno));
    return DM_ERR_IO;
}
