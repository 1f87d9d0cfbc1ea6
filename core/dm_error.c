#include "dm_error.h"

const char *dm_errname(int code)
{
    switch (code) {
#define DM__NAME(name, c, msg) case (c): return "DM_ERR_" #name;
        DM_ERRORS(DM__NAME)
#undef DM__NAME
    }
    return "DM_ERR_?";
}

const char *dm_strerror(int code)
{
    switch (code) {
#define DM__MSG(name, c, msg) case (c): return msg;
        DM_ERRORS(DM__MSG)
#undef DM__MSG
    }
    return "unknown error";
}

int dm_exit_code(int code)
{
    switch (code) {
    case DM_ERR_OK:
        return 0;
    case DM_ERR_ARG: case DM_ERR_PARSE: case DM_ERR_RANGE: case DM_ERR_UNKNOWN:
    case DM_ERR_NOTFOUND: case DM_ERR_IO:
        return 2;
    case DM_ERR_STORE: case DM_ERR_BUSY: case DM_ERR_CHILD: case DM_ERR_GL:
        return DM_EXIT_ENV;
    }
    return 1;
}
