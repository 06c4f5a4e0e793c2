/* diag.c: error message formatting (see diag.h). */
#include "core/diag.h"

#include <stdarg.h>
#include <stdio.h>

mcrt_status mc_fail(mc_diag *d, mcrt_status status, const char *fmt, ...)
{
    va_list ap;
    if (!d)
        return status;
    va_start(ap, fmt);
    vsnprintf(d->msg, sizeof d->msg, fmt, ap);
    va_end(ap);
    return status;
}
