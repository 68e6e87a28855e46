/* src/core/error.c: cu_fail, the formatter behind every error the library returns, and cu_escape for what they quote. */
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

const char *cu_escape(char *dst, size_t n, const char *src)
{
    static const char hex[] = "0123456789abcdef";
    size_t o = 0;
    for (const unsigned char *p = (const unsigned char *)src; *p && o + 1 < n; p++) {
        if (*p >= 32 && *p != 127) {
            dst[o++] = (char)*p;
        } else if (o + 4 < n) {
            dst[o++] = '\\';
            dst[o++] = 'x';
            dst[o++] = hex[*p >> 4];
            dst[o++] = hex[*p & 15];
        } else {
            break;
        }
    }
    if (n)
        dst[o] = 0;
    return dst;
}
