/* src/core/error.h: the library's one error convention: functions that can fail return non-zero and fill a cu_error. */
#ifndef CU_ERROR_H
#define CU_ERROR_H
#include "cumulo.h"

#if defined(__GNUC__)
#define CU_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define CU_PRINTF(f, a)
#endif

/* Formats a one-line message into *err (err may be NULL) and returns 1, so a failing path reads
 * `return cu_fail(err, "%s:%d: ...", path, line);`. */
int cu_fail(cu_error *err, const char *fmt, ...) CU_PRINTF(2, 3);
#endif
