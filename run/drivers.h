/* drivers.h — which OpenGL driver dmbench measures (docs/drivers.md).
 *
 * A driver is chosen for a whole process tree by DMBENCH_DRIVER:
 *   default       whatever EGL gives (the system's Mesa; llvmpipe here)
 *   llvmpipe      the system's Mesa, llvmpipe forced (GALLIUM_DRIVER)
 *   llvmpipe-25   llvmpipe of Mesa 25 unpacked by scripts/install-mesa25
 *   zink          zink over lavapipe of that Mesa 25 (GL over Vulkan)
 * The Mesa 25 drivers need their libraries on the loader's path before any
 * library of the system's Mesa is loaded, so drivers_enter() sets the
 * variables and re-executes the program once; the measuring children, the
 * Valgrind child and the viewer inherit them.
 */
#ifndef RUN_DRIVERS_H
#define RUN_DRIVERS_H

#include <stddef.h>
#include "core/dm_util.h"

typedef struct driver_info {
    const char *name;
    const char *meaning;
    int mesa25;          /* needs the Mesa 25 prefix */
    const char *gallium; /* GALLIUM_DRIVER, or NULL */
} driver_info;

/* The drivers dmbench knows, NULL-terminated by a zero row. */
const driver_info *drivers_list(void);
const driver_info *drivers_find(const char *name);
/* Directory of the Mesa 25 prefix: DMBENCH_MESA25_PREFIX or
 * /opt/dmbench/mesa-25 (not checked). */
const char *drivers_mesa25_prefix(void);
/* NULL when driver d can run here, else why not (static text or allocated
 * into *why_buf, which the caller frees). */
const char *drivers_missing(const driver_info *d, char **why_buf);
/* The name of the driver this process runs ("default" when none chosen),
 * as drivers_enter found it: the marker it sets for the re-executed process
 * counts only in that process tree, never when inherited from a user's
 * environment. */
const char *drivers_current(void);
/* Applies DMBENCH_DRIVER: 0 when nothing is to be done or the process
 * already runs under it; otherwise sets the driver's variables and
 * execv()s argv[0] via /proc/self/exe (it returns only on error).
 * DM_ERR_ARG for an unknown driver, DM_ERR_UNSUPPORTED for one that cannot
 * run here, with the message in err. */
int drivers_enter(char **argv, dm_str *err);

#endif
