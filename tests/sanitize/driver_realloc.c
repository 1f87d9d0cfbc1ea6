/* driver_realloc.c — linked into the GL tests of the sanitizer tree only
 * (tests/CMakeLists.txt, dm_add_gl with DM_SANITIZE).
 *
 * llvmpipe's tessellation (Mesa's draw module) grows its output arrays with
 * one realloc per patch.  glibc grows a large block in place or by mremap;
 * AddressSanitizer's realloc always allocates anew, copies and frees, and
 * every new large block is a fresh mapping: the copies grow with the square
 * of the patches, and the page faults took half the CPU time of a
 * tessellated GL test (test_techniques_cylinder_caps: 6.1 million page
 * faults, 22 s of system time, against 0.1 million and 0.4 s in the normal
 * build; perf record -e page-faults, 2026-11-29).
 *
 * This realloc, defined in the executable, takes every call of the
 * process: a call from inside the GL driver (its return address in a
 * library named *_dri.so or libgallium*) gets 4 times the block's size
 * when it must grow (or what it asks, if more), and keeps its block when
 * that already holds the size, so the copies add up to about a third of
 * the final size; every other
 * call, ours included, goes to AddressSanitizer's realloc unchanged, with
 * its exact bounds checked.  The driver is not what the sanitizer tree
 * tests: the bytes past its asked size are not checked. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include <dlfcn.h>
#include <malloc.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

void *realloc(void *p, size_t n);

typedef void *(*realloc_fn)(void *, size_t);

/* Each call site seen (return address) and whether it is in the driver:
 * an open-addressed table, at most a few dozen sites in a process. */
#define SITES 1024
static struct { uintptr_t ret; int driver; } sites[SITES];

static int in_driver(uintptr_t ret)
{
    size_t h = (ret >> 4) % SITES;
    for (size_t k = 0; k < SITES; k++, h = (h + 1) % SITES) {
        uintptr_t seen = __atomic_load_n(&sites[h].ret, __ATOMIC_ACQUIRE);   /* after its driver flag */
        if (seen == ret)
            return sites[h].driver;
        if (seen == 0) {   /* two threads may both fill it: with the same answer */
            Dl_info info;
            const char *f = dladdr((void *)ret, &info) && info.dli_fname ? info.dli_fname : "";
            const char *base = strrchr(f, '/') ? strrchr(f, '/') + 1 : f;
            int driver = strstr(base, "_dri.so") != NULL || strncmp(base, "libgallium", 10) == 0;
            sites[h].driver = driver;
            __atomic_store_n(&sites[h].ret, ret, __ATOMIC_RELEASE);
            return driver;
        }
    }
    return 0;   /* table full: as everyone else */
}

void *realloc(void *p, size_t n)
{
    static realloc_fn next;
    if (!next)
        next = (realloc_fn)dlsym(RTLD_NEXT, "realloc");
    uintptr_t ret = (uintptr_t)__builtin_return_address(0);
    if (!p || n == 0 || !in_driver(ret))
        return next(p, n);
    size_t have = malloc_usable_size(p);
    if (n <= have)
        return p;
    size_t grown = 4 * have;
    return next(p, grown > n ? grown : n);
}
