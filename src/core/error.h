/* src/core/error.h: the library's one error convention: functions that can fail return non-zero and fill a cu_error. */
#ifndef CU_ERROR_H
#define CU_ERROR_H
#include "cumulo.h"

#if defined(__GNUC__)
#define CU_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define CU_PRINTF(f, a)

/* Copies src into dst (n bytes, always terminated) with every control byte written as \xHH, so text quoted back
 * from a file or the command line cannot drive the terminal that shows the message (ESC sequences, BEL). */
const char *cu_escape(char *dst, size_t n, const char *src);
#endif

/* Formats a one-line message into *err (err may be NULL) and returns 1, so a failing path reads
 * `return cu_fail(err, "%s:%d: ...", path, line);`. */
int cu_fail(cu_error *err, const char *fmt, ...) CU_PRINTF(2, 3);

/* Copies src into dst (n bytes, always terminated) with every control byte written as \xHH, so text quoted back
 * from a file or the command line cannot drive the terminal that shows the message (ESC sequences, BEL). */
const char *cu_escape(char *dst, size_t n, const char *src);
#endif
