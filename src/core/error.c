/* src/core/error.c: cu_fail, the formatter behind every error the library returns. */
#include "error.h"
#include <stdarg.h>
#include <stdio.h>

int cu_fail(cu_error *err, const char *fmt, ...)
{
    if (!err)
        return 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    return 1;
}
