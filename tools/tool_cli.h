/* tools/tool_cli.h: what the offline tools' command lines share: whole-string integer lists that reject overflow,
 * and the checked close of an output file. Header-only, so that every tool keeps its one-line link rule. */
#ifndef CU_TOOL_CLI_H
#define CU_TOOL_CLI_H
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

/* Reads v as exactly n unsigned decimal integers separated by sep ("64x48", "8,6,4", "12"), each in [lo, hi], into
 * out: 0, or -1 for anything else. Digits only, no sign, space or exponent; strtoull's ERANGE is an error, so a value
 * past 2^64 is rejected instead of wrapping (sscanf's %d turned 4294967360 into 64). */
static inline int tool_parse_uints(const char *v, char sep, int n, unsigned long long lo, unsigned long long hi,
                                   unsigned long long *out)
{
    for (int i = 0; i < n; i++) {
        if (!v || *v < '0' || *v > '9')
            return -1;
        char *end;
        errno = 0;
        unsigned long long x = strtoull(v, &end, 10);
        if (errno == ERANGE || x < lo || x > hi || *end != (i == n - 1 ? '\0' : sep))
            return -1;
        out[i] = x;
        v = end + 1;
    }
    return 0;
}

/* One integer of [lo, hi] as an int (hi must fit in one). */
static inline int tool_parse_int(const char *v, int lo, int hi, int *out)
{
    unsigned long long x;
    if (lo < 0 || tool_parse_uints(v, 0, 1, (unsigned long long)lo, (unsigned long long)hi, &x))
        return -1;
    *out = (int)x;
    return 0;
}

/* Closes an output file (stdout is flushed, not closed): 0, or -1 when any write to it or the close failed, e.g. a
 * full disk, where fprintf's errors are only remembered in the stream's error flag. */
static inline int tool_close_output(FILE *f)
{
    int bad = ferror(f);
    bad |= f == stdout ? fflush(f) : fclose(f);
    return bad ? -1 : 0;
}
#endif
