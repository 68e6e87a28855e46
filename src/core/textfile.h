/* src/core/textfile.h: the line reader of the table loaders (Mie phase table, slab model, collector): lines split
 * into blank-separated tokens with their line numbers, comments and blank lines skipped, strict numbers. */
#ifndef CU_TEXTFILE_H
#define CU_TEXTFILE_H
#include "cumulo.h"
#include <stdio.h>

/* Lines are bounded so that a binary file or a runaway writer is caught at the first line, not after reading it
 * whole; 510 characters hold any row these tables have. */
enum { CU_TEXT_MAX_LINE = 510, CU_TEXT_MAX_TOKENS = 16 };

typedef struct cu_textfile {
    const char *path;
    FILE *fp;
    char *buf;
    size_t cap;
    int line;                         /* the line last read (1-based); at the end, the number of lines */
    int ntok;                         /* tokens on that line, all of them, even past CU_TEXT_MAX_TOKENS */
    char *tok[CU_TEXT_MAX_TOKENS];    /* the first ones, NUL-terminated in place */
} cu_textfile;

/* Opens path; on failure fills err with "PATH: cannot open WHAT: REASON (HINT)" and returns 1. */
int cu_textfile_open(cu_textfile *f, const char *path, const char *what, const char *hint, cu_error *err);

/* Reads up to the next line that has a token: a token starting with '#' and what follows it are a comment. Returns 1
 * with the line in f->tok, 0 at the end of the file, -1 with err filled ("PATH:LINE: ...") for a line longer than
 * CU_TEXT_MAX_LINE, a NUL or other control byte (tab and CR aside) or a read error. */
int cu_textfile_next(cu_textfile *f, cu_error *err);

void cu_textfile_close(cu_textfile *f);

/* The same reader over text[0..len), named name in messages: the loaders' in-memory entries (fuzz targets, tests). */
int cu_textfile_open_mem(cu_textfile *f, const char *name, const char *text, size_t len, cu_error *err);

/* How a token reads as a number: the whole token must be one strtod number, finite, and finite once stored as a
 * float, since the tables end up in float textures (a double such as 1e39 would become inf there). */
typedef enum { CU_NUM_OK = 0, CU_NUM_BAD, CU_NUM_NOT_FLOAT } cu_num_status;
cu_num_status cu_text_number(const char *tok, double *v);

/* Fills err with "PATH:LINE: field 'NAME': 'TOKEN' does not fit in a float ..." and returns 1: the one message for
 * CU_NUM_NOT_FLOAT, so that every loader words it alike. */
int cu_text_fail_float(const cu_textfile *f, cu_error *err, const char *field, const char *tok);
#endif
