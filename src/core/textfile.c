/* src/core/textfile.c: the line reader of the table loaders (see textfile.h). */
#include "textfile.h"
#include "error.h"
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int cu_textfile_open(cu_textfile *f, const char *path, const char *what, const char *hint, cu_error *err)
{
    memset(f, 0, sizeof *f);
    f->path = path;
    f->fp = fopen(path, "r");
    if (!f->fp)
        return cu_fail(err, "%s: cannot open %s: %s (%s)", path, what, strerror(errno), hint);
    return 0;
}

int cu_textfile_open_mem(cu_textfile *f, const char *name, const char *text, size_t len, cu_error *err)
{
    memset(f, 0, sizeof *f);
    f->path = name;
    /* fmemopen only reads a "r" stream, so the cast drops no promise; an empty buffer reads as an empty file. */
    f->fp = fmemopen(len ? (void *)text : (void *)"", len, "r");
    if (!f->fp)
        return cu_fail(err, "%s: cannot read the table from memory: %s", name, strerror(errno));
    return 0;
}

static int blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

int cu_textfile_next(cu_textfile *f, cu_error *err)
{
    for (;;) {
        errno = 0;
        ssize_t len = getline(&f->buf, &f->cap, f->fp);
        if (len < 0) {
            if (ferror(f->fp))
                return -cu_fail(err, "%s:%d: read error: %s", f->path, f->line + 1, strerror(errno));
            return 0;
        }
        f->line++;
        if (memchr(f->buf, 0, (size_t)len))
            return -cu_fail(err, "%s:%d: NUL byte in the line", f->path, f->line);
        /* Nor any other control byte: a token that held one would be quoted back in a message, to a terminal. */
        for (ssize_t i = 0; i < len; i++) {
            unsigned char c = (unsigned char)f->buf[i];
            if ((c < 32 && c != '\t' && c != '\r' && c != '\n') || c == 127)
                return -cu_fail(err, "%s:%d: not a text file (byte 0x%02x)", f->path, f->line, c);
        }
        if (len - (len > 0 && f->buf[len - 1] == '\n') > CU_TEXT_MAX_LINE)
            return -cu_fail(err, "%s:%d: line longer than %d characters", f->path, f->line, CU_TEXT_MAX_LINE);
        f->ntok = 0;
        char *p = f->buf;
        if (f->line == 1 && len >= 3 && !memcmp(p, "\xef\xbb\xbf", 3))
            p += 3; /* a UTF-8 byte-order mark is not text */
        for (;;) {
            while (blank(*p))
                p++;
            if (!*p || *p == '#')
                break;
            if (f->ntok < CU_TEXT_MAX_TOKENS)
                f->tok[f->ntok] = p;
            f->ntok++;
            while (*p && !blank(*p))
                p++;
            if (*p)
                *p++ = 0;
        }
        if (f->ntok > 0)
            return 1;
    }
}

void cu_textfile_close(cu_textfile *f)
{
    if (f->fp)
        fclose(f->fp);
    free(f->buf);
    f->fp = NULL;
    f->buf = NULL;
}

cu_num_status cu_text_number(const char *tok, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(tok, &end);
    if (end == tok || *end || errno == ERANGE || !isfinite(*v))
        return CU_NUM_BAD;
    return fabs(*v) > FLT_MAX ? CU_NUM_NOT_FLOAT : CU_NUM_OK;
}

int cu_text_fail_float(const cu_textfile *f, cu_error *err, const char *field, const char *tok)
{
    return cu_fail(err, "%s:%d: field '%s': '%.40s' does not fit in a float (|x| <= %.4g)", f->path, f->line, field,
                   tok, FLT_MAX);
}
