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
