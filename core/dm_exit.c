#include "dm_exit.h"
#include "dm_error.h"

#include <stddef.h>

dm_exit dm_exit_from_error(int err)
{
    switch (err) {
    case DM_ERR_OK:
        return DM_EXIT_OK;
    case DM_ERR_ARG:
    case DM_ERR_PARSE:
    case DM_ERR_RANGE:
    case DM_ERR_UNKNOWN:
    case DM_ERR_NOTFOUND:
    case DM_ERR_EXISTS:
    case DM_ERR_IO:
    case DM_ERR_UNSUPPORTED:
        return DM_EXIT_USAGE;
    case DM_ERR_STORE:           /* damaged, locked or full store */
    case DM_ERR_BUSY:            /* the output is in use by another run */
    case DM_ERR_CHILD:           /* measuring processes that keep dying */
    case DM_ERR_GL:              /* no usable GL context */
    case DM_ERR_DISK:            /* a disk full, over quota or past ulimit -f */
    case DM_ERR_NOMEM:           /* an allocation the machine refused */
        return DM_EXIT_ENV;
    default:
        return DM_EXIT_FAILED;
    }
}

const char *dm_exit_meaning(int code)
{
    switch (code) {
#define DM__EXIT_MEANING(name, c, meaning) case (c): return meaning;
        DM_EXITS(DM__EXIT_MEANING)
#undef DM__EXIT_MEANING
    }
    return NULL;
}
