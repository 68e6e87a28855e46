/* platform/input/input_set.c: the inputs of one run together (see input_set.h). */
#include "input_set.h"
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#define READ_MAX 64     /* actions one read of one input hands over */

static void say(const cu_input_set *s, const char *msg)
{
    if (s->opts.log)
        s->opts.log(s->opts.log_user, msg);
}

int cu_input_set_add(cu_input_set *s, const char *spec, char *err, size_t errlen)
{
    if (s->n == CU_INPUT_SET_MAX) {
        snprintf(err, errlen, "at most %d --input options", CU_INPUT_SET_MAX);
        return 1;
    }
    if (cu_input_parse(spec, &s->slot[s->n].spec, err, errlen))
        return 1;
    s->slot[s->n++].required = 1;
    s->nrequired++;
    return 0;
}

void cu_input_set_add_stdin(cu_input_set *s)
{
    for (int i = 0; i < s->n; i++)
        if (s->slot[i].spec.kind == CU_INPUT_STDIN)
            return;
    if (s->n < CU_INPUT_SET_MAX)
        s->slot[s->n++].spec.kind = CU_INPUT_STDIN;
}

static int open_slot(cu_input_set *s, cu_input_slot *sl)
{
    char msg[1024], desc[300];
    cu_input_describe(&sl->spec, desc, sizeof desc);
    sl->be = cu_input_find(sl->spec.kind);
    if (!sl->be) {
        snprintf(msg, sizeof msg, "%s; continuing without %s", cu_input_missing(sl->spec.kind), desc);
        say(s, msg);
        return 1;
    }
    if (sl->be->open(&sl->in, &sl->spec, &s->opts, msg, sizeof msg - 32)) {
        sl->in = NULL;
        strcat(msg, "; continuing without it");
        say(s, msg);
        return 1;
    }
    if (msg[0])
        say(s, msg);
    return 0;
}

int cu_input_set_open(cu_input_set *s, const cu_input_opts *opts)
{
    int opened = 0;
    s->opts = *opts;
    for (int i = 0; i < s->n; i++)
        if (open_slot(s, &s->slot[i]) == 0)
            opened += s->slot[i].required;
    return opened;
}

static void close_slot(cu_input_slot *sl)
{
    if (sl->in)
        sl->be->close(sl->in);
    sl->in = NULL;
}

int cu_input_set_poll(cu_input_set *s, int timeout_ms, cu_action *acts, const char **source, int max)
{
    struct pollfd pfd[CU_INPUT_SET_MAX * CU_INPUT_FDS_MAX];
    int owner[CU_INPUT_SET_MAX * CU_INPUT_FDS_MAX], n = 0, count = 0;
    for (int i = 0; i < s->n; i++) {
        int fds[CU_INPUT_FDS_MAX];
        int k = s->slot[i].in ? s->slot[i].be->fds(s->slot[i].in, fds, CU_INPUT_FDS_MAX) : 0;
        for (int j = 0; j < k; j++, n++) {
            pfd[n] = (struct pollfd){ .fd = fds[j], .events = POLLIN };
            owner[n] = i;
        }
    }
    if (n == 0) {
        struct timespec ts = { 0, (long)timeout_ms * 1000000L };
        if (timeout_ms > 0)
            nanosleep(&ts, NULL);
        return 0;
    }
    if (poll(pfd, (nfds_t)n, timeout_ms) <= 0)
        return 0;
    int done[CU_INPUT_SET_MAX] = {0};
    for (int p = 0; p < n; p++) {
        cu_input_slot *sl = &s->slot[owner[p]];
        if (!pfd[p].revents || done[owner[p]] || !sl->in)
            continue;
        done[owner[p]] = 1; /* an input with several fds is read once: its read drains them all */
        cu_action got[READ_MAX];
        char err[512];
        int na = 0;
        cu_input_status st = sl->be->read(sl->in, got, READ_MAX, &na, err, sizeof err);
        for (int k = 0; k < na && count < max; k++) {
            source[count] = sl->be->name;
            acts[count++] = got[k];
        }
        if (st == CU_INPUT_READ_GONE)
            say(s, err);
        if (st != CU_INPUT_READ_OK)
            close_slot(sl);
        sl->ended |= st == CU_INPUT_READ_ENDED; /* a script ended, or the service has no terminal */
    }
    return count;
}

void cu_input_set_describe(const cu_input_set *s, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < s->n && used < len; i++) {
        char d[300];
        if (!s->slot[i].in)
            continue;
        cu_input_describe(&s->slot[i].spec, d, sizeof d);
        snprintf(buf + used, len - used, "%s%s", used ? ", " : "", d);
        used = strlen(buf);
    }
}

int cu_input_set_left(const cu_input_set *s, int *open, int *ended)
{
    int left = 0;
    *open = *ended = 0;
    for (int i = 0; i < s->n; i++) {
        left += s->slot[i].required && (s->slot[i].in || s->slot[i].ended);
        *open |= s->slot[i].in != NULL;
        *ended |= s->slot[i].ended;
    }
    return left;
}

void cu_input_set_close(cu_input_set *s)
{
    for (int i = 0; i < s->n; i++)
        close_slot(&s->slot[i]);
}
