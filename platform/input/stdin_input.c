/* platform/input/stdin_input.c: the stdin command language of `cumulo run` (sun, turn, toggle, quit...), its line
 * reader, and the "stdin" input back end built on them. */
#include "stdin_input.h"
#include "input_backend.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define CMDS "sun EL AZ, elevation EL, azimuth AZ, turn N, toggle, offset MINUTES, status, quit"

/* Splits into at most 4 words; returns the count, or 5 for too many. */
static int split(char *s, char *w[4])
{
    int n = 0;
    for (char *p = strtok(s, " \t\r"); p; p = strtok(NULL, " \t\r")) {
        if (n == 4)
            return 5;
        w[n++] = p;
    }
    return n;
}

/* What the user typed, fit to be echoed in a message: at most 40 bytes of it, every byte that is not printable ASCII
 * (a control, an escape sequence's ESC, DEL, a byte of UTF-8) written as \xNN, so nothing reaches the terminal as a
 * command to it. */
static const char *shown(const char *w, char buf[4 * 40 + 1])
{
    char *o = buf;
    for (int i = 0; w[i] && i < 40; i++) {
        unsigned char c = (unsigned char)w[i];
        if (c >= 0x20 && c < 0x7f)
            *o++ = (char)c;
        else
            o += sprintf(o, "\\x%02x", c);
    }
    *o = 0;
    return buf;
}

static int number(const char *w, double lo, double hi, double *out)
{
    char *end;
    double x = strtod(w, &end);
    if (end == w || *end || !isfinite(x) || x < lo || x > hi)
        return 1;
    *out = x;
    return 0;
}

int cu_stdin_parse(const char *line, cu_action *out, char *err, size_t errlen)
{
    char tmp[4 * CU_STDIN_LINE_MAX];
    char *w[4];
    cu_action z = {0};
    *out = z;
    /* Escaped before it is split: no word, and so no message quoting one, holds a control byte; no command has one. */
    cu_input_escape(tmp, sizeof tmp, line, "\t\r");
    char *hash = strchr(tmp, '#');
    if (hash)
        *hash = '\0';
    int n = split(tmp, w);
    if (n == 0)
        return 0;
    const char *c = w[0];
    double x, y;
    char shw[4 * 40 + 1];
    if (!strcmp(c, "sun")) {
        if (n != 3) {
            snprintf(err, errlen, "stdin: 'sun' needs elevation and azimuth in degrees, e.g. 'sun 35 120'");
            return 1;
        }
        if (number(w[1], -90, 90, &x)) {
            snprintf(err, errlen, "stdin: 'sun': elevation '%s' is not a number in -90..90", shown(w[1], shw));
            return 1;
        }
        if (number(w[2], -1e6, 1e6, &y)) {
            snprintf(err, errlen, "stdin: 'sun': azimuth '%s' is not a number of degrees", shown(w[2], shw));
            return 1;
        }
        out->kind = CU_ACT_SET_SUN;
        out->el = x;
        out->az = y;
        return 0;
    }
    if (!strcmp(c, "elevation") || !strcmp(c, "el") || !strcmp(c, "azimuth") || !strcmp(c, "az")) {
        int el = c[1] == 'l';
        if (n != 2 || number(w[1], el ? -90 : -1e6, el ? 90 : 1e6, &x)) {
            snprintf(err, errlen, "stdin: '%s' needs one number of degrees%s", c, el ? " in -90..90" : "");
            return 1;
        }
        out->kind = el ? CU_ACT_SET_EL : CU_ACT_SET_AZ;
        out->el = el ? x : 0;
        out->az = el ? 0 : x;
        return 0;
    }
    if (!strcmp(c, "turn")) {
        if (n != 2 || number(w[1], -10000, 10000, &x) || x != floor(x)) {
            snprintf(err, errlen, "stdin: 'turn' needs a whole number of detents in -10000..10000");
            return 1;
        }
        out->kind = CU_ACT_TURN;
        out->detents = (int)x;
        return 0;
    }
    if (!strcmp(c, "offset")) {
        if (n != 2 || number(w[1], -CU_OFFSET_MAX_MIN, CU_OFFSET_MAX_MIN, &x)) {
            snprintf(err, errlen, "stdin: 'offset' needs minutes in -%d..%d, e.g. 'offset 90'", CU_OFFSET_MAX_MIN,
                     CU_OFFSET_MAX_MIN);
            return 1;
        }
        out->kind = CU_ACT_SET_OFFSET;
        out->minutes = x;
        return 0;
    }
    struct { const char *name; cu_action_kind kind; } simple[] = {
        { "toggle", CU_ACT_TOGGLE }, { "button", CU_ACT_TOGGLE }, { "status", CU_ACT_STATUS },
        { "quit", CU_ACT_QUIT }, { "exit", CU_ACT_QUIT },
    };
    for (size_t i = 0; i < sizeof simple / sizeof simple[0]; i++) {
        if (!strcmp(c, simple[i].name)) {
            if (n != 1) {
                snprintf(err, errlen, "stdin: '%s' takes no arguments", shown(c, shw));
                return 1;
            }
            out->kind = simple[i].kind;
            return 0;
        }
    }
    snprintf(err, errlen, "stdin: unknown command '%s' (commands: " CMDS ")", shown(c, shw));
    return 1;
}

void cu_stdin_init(cu_stdin *s, int fd)
{
    s->fd = fd;
    s->len = 0;
    s->overlong = 0;
    s->eof = 0;
}

void cu_stdin_feed(cu_stdin *s, const char *data, size_t n, void (*fn)(void *user, const char *line), void *user)
{
    for (size_t i = 0; i < n; i++) {
        char ch = data[i];
        if (ch == '\n') {
            if (!s->overlong) {
                s->buf[s->len] = '\0';
                fn(user, s->buf);
            }
            s->len = 0;
            s->overlong = 0;
        } else if (s->overlong) {
            continue;
        } else if (s->len + 1 >= sizeof s->buf) {
            /* A line this long is not a command: drop it whole rather than run its tail as one. */
            s->overlong = 1;
            s->len = 0;
            fn(user, CU_STDIN_OVERLONG);
        } else {
            s->buf[s->len++] = ch;
        }
    }
}

int cu_stdin_read(cu_stdin *s, void (*fn)(void *user, const char *line), void *user)
{
    /* One read per call: stdin stays blocking (making it non-blocking would change the terminal's or the parent's
     * file description too), so the caller polls first and a single read never waits. */
    char data[512];
    ssize_t r = read(s->fd, data, sizeof data);
    if (r > 0) {
        cu_stdin_feed(s, data, (size_t)r, fn, user);
        return 0;
    }
    if (r < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))
        return 0;
    /* End of file: a last line without a newline still counts. */
    if (s->len && !s->overlong) {
        s->buf[s->len] = '\0';
        s->len = 0;
        fn(user, s->buf);
    }
    s->eof = 1;
    return 1;
}

/* ------------------------------------------------------------------ the "stdin" input back end */

struct cu_input {
    cu_stdin in;
    cu_input_opts opts;
    cu_action *acts;    /* where the lines of the current read() go */
    int max, n;
};

static void say(cu_input *in, const char *msg)
{
    if (in->opts.log)
        in->opts.log(in->opts.log_user, msg);
}

static void on_line(void *user, const char *line)
{
    cu_input *in = user;
    cu_action a;
    char err[256];
    if (!strcmp(line, CU_STDIN_OVERLONG)) {
        snprintf(err, sizeof err, "stdin: line longer than %d characters ignored", CU_STDIN_LINE_MAX - 1);
        say(in, err);
    } else if (cu_stdin_parse(line, &a, err, sizeof err)) {
        say(in, err); /* a typo in one command must not end the session */
    } else if (a.kind != CU_ACT_NONE && in->n < in->max) {
        in->acts[in->n++] = a;
    }
}

static int stdin_open(cu_input **out, const cu_input_spec *spec, const cu_input_opts *opts, char *msg, size_t len)
{
    (void)spec;
    *out = calloc(1, sizeof **out);
    if (!*out) {
        snprintf(msg, len, "stdin: out of memory");
        return 1;
    }
    cu_stdin_init(&(*out)->in, STDIN_FILENO);
    (*out)->opts = *opts;
    if (len)
        msg[0] = '\0';
    return 0;
}

static int stdin_fds(cu_input *in, int *fds, int max)
{
    if (max < 1)
        return 0;
    fds[0] = in->in.fd;
    return 1;
}

static cu_input_status stdin_read(cu_input *in, cu_action *acts, int max, int *n, char *err, size_t errlen)
{
    (void)err;
    (void)errlen;
    in->acts = acts;
    in->max = max;
    in->n = 0;
    int ended = cu_stdin_read(&in->in, on_line, in);
    *n = in->n;
    return ended ? CU_INPUT_READ_ENDED : CU_INPUT_READ_OK;
}

static void stdin_close(cu_input *in)
{
    free(in); /* the descriptor is the process's, not ours to close */
}

const cu_input_backend cu_input_stdin = {
    .name = "stdin",
    .kind = CU_INPUT_STDIN,
    .open = stdin_open,
    .fds = stdin_fds,
    .read = stdin_read,
    .close = stdin_close,
};
