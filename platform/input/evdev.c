/* platform/input/evdev.c: decoding of Linux input events into sun actions, opening/reading /dev/input/event*
 * devices, and the "evdev" input back end built on them. */
#include "evdev.h"
#include "input_backend.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#ifndef input_event_sec
#define input_event_sec time.tv_sec
#define input_event_usec time.tv_usec
#endif

static uint64_t event_ns(const struct input_event *ev)
{
    return (uint64_t)ev->input_event_sec * 1000000000u + (uint64_t)ev->input_event_usec * 1000u;
}

int cu_evdev_decode(cu_evdev_decoder *d, const struct input_event *ev, cu_action *out)
{
    cu_action z = {0};
    *out = z;
    out->t_ns = event_ns(ev);
    if (ev->type == EV_SYN) {
        if (ev->code == SYN_DROPPED)
            d->dropping = 1;
        else if (ev->code == SYN_REPORT)
            d->dropping = 0;
        return 0;
    }
    if (d->dropping)
        return 0; /* half a report: a partial dial movement is worse than none */
    if (ev->type == EV_REL) {
        if (ev->code == REL_DIAL || ev->code == REL_WHEEL || ev->code == REL_HWHEEL ||
            (ev->code == REL_X && d->rel_x_is_knob)) {
            if (ev->value == 0)
                return 0;
            out->kind = CU_ACT_TURN;
            out->detents = ev->value;
            return 1;
        }
        return 0;
    }
    if (ev->type != EV_KEY || ev->value == 0)
        return 0; /* releases do nothing */
    int repeat = ev->value == 2;
    switch (ev->code) {
    case KEY_LEFT:  out->kind = CU_ACT_TURN_AZ; out->detents = -1; return 1;
    case KEY_RIGHT: out->kind = CU_ACT_TURN_AZ; out->detents = 1;  return 1;
    case KEY_UP:    out->kind = CU_ACT_TURN_EL; out->detents = 1;  return 1;
    case KEY_DOWN:  out->kind = CU_ACT_TURN_EL; out->detents = -1; return 1;
    case KEY_KPPLUS: case KEY_EQUAL: case KEY_VOLUMEUP:
        out->kind = CU_ACT_TURN; out->detents = 1; return 1;
    case KEY_KPMINUS: case KEY_MINUS: case KEY_VOLUMEDOWN:
        out->kind = CU_ACT_TURN; out->detents = -1; return 1;
    case KEY_ENTER: case KEY_KPENTER: case KEY_SPACE: case KEY_MUTE: case BTN_0:
        if (repeat)
            return 0; /* holding the button must not flip the axis back and forth */
        out->kind = CU_ACT_TOGGLE;
        return 1;
    case KEY_Q: case KEY_ESC:
        if (repeat)
            return 0;
        out->kind = CU_ACT_QUIT;
        return 1;
    default:
        return 0;
    }
}

static int bit(const unsigned char *bits, size_t len, unsigned n)
{
    return n / 8 < len && (bits[n / 8] >> (n % 8)) & 1;
}

int cu_evdev_rel_x_is_knob(const unsigned char *key_bits, size_t key_len, const unsigned char *rel_bits,
                           size_t rel_len)
{
    return bit(rel_bits, rel_len, REL_X) && !bit(key_bits, key_len, BTN_LEFT) && !bit(rel_bits, rel_len, REL_Y);
}

struct cu_evdev {
    int fd;
    char path[300];
    char name[128];
    cu_evdev_decoder dec;
};

static int open_error(const char *what, int e, char *err, size_t errlen)
{
    if (e == EACCES || e == EPERM)
        snprintf(err, errlen, "evdev: %s: permission denied: add the user to group 'input' "
                 "(sudo usermod -aG input $USER, then log in again) or run as root", what);
    else if (e == ENOENT || e == ENODEV || e == ENXIO)
        snprintf(err, errlen, "evdev: %s: no such device: is it plugged in? (list devices: "
                 "cat /proc/bus/input/devices)", what);
    else
        snprintf(err, errlen, "evdev: %s: %s", what, strerror(e));
    return 1;
}

/* Finds /dev/input/eventN whose name is `want` (exact first, then containing it). */
static int find_by_name(const char *want, char *path, size_t plen, char *err, size_t errlen)
{
    DIR *dir = opendir("/dev/input");
    if (!dir) {
        snprintf(err, errlen, "evdev: no device named '%s': /dev/input does not exist (no input devices on this "
                 "machine)", want);
        return 1;
    }
    char sub[300] = "";
    int denied = 0, found = 0;
    struct dirent *de;
    while (!found && (de = readdir(dir))) {
        if (strncmp(de->d_name, "event", 5))
            continue;
        char p[300], name[256] = "";
        snprintf(p, sizeof p, "/dev/input/%s", de->d_name);
        int fd = open(p, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
        if (fd < 0) {
            denied |= errno == EACCES;
            continue;
        }
        if (ioctl(fd, EVIOCGNAME(sizeof name - 1), name) >= 0) {
            if (!strcmp(name, want)) {
                snprintf(path, plen, "%s", p);
                found = 1;
            } else if (!sub[0] && strstr(name, want)) {
                snprintf(sub, sizeof sub, "%s", p);
            }
        }
        close(fd);
    }
    closedir(dir);
    if (found)
        return 0;
    if (sub[0]) {
        snprintf(path, plen, "%s", sub);
        return 0;
    }
    snprintf(err, errlen, "evdev: no device named '%s'%s (names: cat /proc/bus/input/devices)", want,
             denied ? "; some devices were not readable: add the user to group 'input'" : "");
    return 1;
}

int cu_evdev_open(cu_evdev **out, const cu_input_spec *spec, int grab, char *err, size_t errlen)
{
    char path[300];
    *out = NULL;
    if (spec->path[0])
        snprintf(path, sizeof path, "%s", spec->path);
    else if (find_by_name(spec->name, path, sizeof path, err, errlen))
        return 1;
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return open_error(path, errno, err, errlen);
    int version;
    if (ioctl(fd, EVIOCGVERSION, &version) < 0) {
        close(fd);
        snprintf(err, errlen, "evdev: %s is not an input event device (give /dev/input/eventN)", path);
        return 1;
    }
    cu_evdev *e = calloc(1, sizeof *e);
    if (!e) {
        close(fd);
        snprintf(err, errlen, "evdev: %s: out of memory", path);
        return 1;
    }
    e->fd = fd;
    snprintf(e->path, sizeof e->path, "%s", path);
    if (ioctl(fd, EVIOCGNAME(sizeof e->name - 1), e->name) < 0)
        snprintf(e->name, sizeof e->name, "?");
    unsigned char keys[KEY_MAX / 8 + 1] = {0}, rels[REL_MAX / 8 + 1] = {0};
    ioctl(fd, EVIOCGBIT(EV_KEY, sizeof keys), keys);
    ioctl(fd, EVIOCGBIT(EV_REL, sizeof rels), rels);
    e->dec.rel_x_is_knob = cu_evdev_rel_x_is_knob(keys, sizeof keys, rels, sizeof rels);
    /* Timestamps on the monotonic clock, like GPIO events, so knob speeds compare across devices. */
    int clk = CLOCK_MONOTONIC;
    ioctl(fd, EVIOCSCLOCKID, &clk);
    if (grab)
        ioctl(fd, EVIOCGRAB, (void *)1);
    *out = e;
    return 0;
}

int cu_evdev_fd(const cu_evdev *e) { return e->fd; }
const char *cu_evdev_name(const cu_evdev *e) { return e->name; }

int cu_evdev_read(cu_evdev *e, cu_action *acts, int max, int *n, char *err, size_t errlen)
{
    struct input_event evs[64];
    *n = 0;
    for (;;) {
        ssize_t r = read(e->fd, evs, sizeof evs);
        if (r < 0) {
            if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)
                return 0;
            if (errno == ENODEV)
                snprintf(err, errlen, "evdev: %s ('%s') was unplugged: plug it back in and restart, continuing "
                         "with the other inputs", e->path, e->name);
            else
                snprintf(err, errlen, "evdev: %s ('%s'): %s", e->path, e->name, strerror(errno));
            return 1;
        }
        if (r == 0) {
            snprintf(err, errlen, "evdev: %s ('%s') closed", e->path, e->name);
            return 1;
        }
        size_t count = (size_t)r / sizeof evs[0];
        for (size_t i = 0; i < count && *n < max; i++)
            if (cu_evdev_decode(&e->dec, &evs[i], &acts[*n]))
                (*n)++;
        if (count < sizeof evs / sizeof evs[0] || *n >= max)
            return 0;
    }
}

void cu_evdev_close(cu_evdev *e)
{
    if (!e)
        return;
    close(e->fd);
    free(e);
}

/* ------------------------------------------------------------------ the "evdev" input back end */

struct cu_input {
    cu_evdev *dev;
};

static int evdev_open(cu_input **out, const cu_input_spec *spec, const cu_input_opts *opts, char *msg, size_t len)
{
    cu_input *in = calloc(1, sizeof *in);
    if (!in) {
        snprintf(msg, len, "evdev: out of memory");
        return 1;
    }
    if (cu_evdev_open(&in->dev, spec, opts->grab, msg, len)) {
        free(in);
        return 1;
    }
    char desc[300];
    cu_input_describe(spec, desc, sizeof desc);
    snprintf(msg, len, "input: %s ('%s')", desc, cu_evdev_name(in->dev));
    *out = in;
    return 0;
}

static int evdev_fds(cu_input *in, int *fds, int max)
{
    if (max < 1)
        return 0;
    fds[0] = cu_evdev_fd(in->dev);
    return 1;
}

static cu_input_status evdev_read(cu_input *in, cu_action *acts, int max, int *n, char *err, size_t errlen)
{
    return cu_evdev_read(in->dev, acts, max, n, err, errlen) ? CU_INPUT_READ_GONE : CU_INPUT_READ_OK;
}

static void evdev_close(cu_input *in)
{
    cu_evdev_close(in->dev);
    free(in);
}

const cu_input_backend cu_input_evdev = {
    .name = "evdev",
    .kind = CU_INPUT_EVDEV,
    .open = evdev_open,
    .fds = evdev_fds,
    .read = evdev_read,
    .close = evdev_close,
};
