/* platform/gpio.c: libgpiod glue for the rotary encoder and button (v1 API for Debian 12's libgpiod 1.6, v2 API when
 * built against libgpiod 2.x); edges are timestamp-ordered and decoded by quadrature.c. With v1 a reader thread
 * drains the kernel's per-line queues as edges come (they hold 16 events each), so a long frame loses none. */
#include "gpio.h"
#include "quadrature.h"
#include <errno.h>
#ifndef CU_TEST_GPIOD_DECLARED /* test_gpio_v2.c declares the v2 API itself to test this file without libgpiod 2 */
#include <gpiod.h>
#endif
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define CONSUMER "cumulo"
#define MAX_EDGES 256
#define RING_EDGES 4096 /* v1: edges the reader thread holds for the main loop (minutes of turning at frame rate) */

enum { LINE_A, LINE_B, LINE_BUTTON, LINE_COUNT };

struct cu_gpio {
    char chip_name[CU_INPUT_NAME_MAX];
    char line_name[LINE_COUNT][CU_INPUT_NAME_MAX];
    unsigned offset[LINE_COUNT];
    int nlines;             /* 2 without a button, 3 with */
    cu_quad quad;
    cu_button button;
    uint64_t t_last;        /* last edge timestamp, so a resync sample never goes back in time */
    char note[256];
    struct gpiod_chip *chip;
#ifdef CU_GPIOD_V2
    struct gpiod_line_request *req;
    struct gpiod_edge_event_buffer *buf;
#else
    struct gpiod_line *line[LINE_COUNT];
    struct gpiod_line_bulk bulk;
    /* The v1 uAPI queues 16 events per line in the kernel, fixed: a frame that takes longer than a few detents
     * (a Pi with heavy settings, the VM test under emulation) overflowed it and lost detents. A reader thread
     * moves edges from the kernel into `ring` as they come; `wake` tells the main loop's poll that edges wait. */
    pthread_t reader;
    int reader_on;
    int wake[2], stop[2];   /* pipes: reader -> main loop (edges queued), main -> reader (quit) */
    pthread_mutex_t mu;     /* guards ring, ring_n, reader_failed, reader_err */
    int mu_on;
    cu_quad_edge ring[RING_EDGES];
    size_t ring_n;
    int reader_failed;
    char reader_err[256];
#endif
};

const char *cu_gpio_api(void)
{
#ifdef CU_GPIOD_V2
    return "libgpiod v2";
#else
    return "libgpiod v1";
#endif
}

const char *cu_gpio_note(const cu_gpio *g) { return g->note; }

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static int chip_error(const char *chip, int e, char *err, size_t errlen)
{
    if (e == EACCES || e == EPERM)
        snprintf(err, errlen, "gpio: %s: permission denied: add the user to group 'gpio' (sudo usermod -aG gpio "
                 "$USER, then log in again) or run as root", chip);
    else if (e == ENOENT || e == ENODEV || e == ENXIO)
        snprintf(err, errlen, "gpio: no GPIO chip '%s' on this machine: check chip= in --input (gpiodetect lists "
                 "the chips)", chip);
    else
        snprintf(err, errlen, "gpio: cannot open GPIO chip '%s': %s", chip, strerror(e));
    return 1;
}

static int busy_error(const cu_gpio *g, int i, const char *consumer, char *err, size_t errlen)
{
    snprintf(err, errlen, "gpio: line %s (offset %u) on %s is busy (used by '%s'): stop that program or remove the "
             "dtoverlay claiming it, or pick other lines", g->line_name[i], g->offset[i], g->chip_name,
             consumer && *consumer ? consumer : "the kernel");
    return 1;
}

/* Feeds sorted-or-not edges of A/B/button (line index, level, time) and emits actions. */
static void decode(cu_gpio *g, cu_quad_edge *edges, size_t n, cu_action *acts, int max, int *count)
{
    cu_quad_edge enc[MAX_EDGES];
    size_t ne = 0;
    cu_quad_sort_edges(edges, n);
    for (size_t i = 0; i < n; i++) {
        if (edges[i].t_ns > g->t_last)
            g->t_last = edges[i].t_ns;
        if (edges[i].line == LINE_BUTTON) {
            if (cu_button_feed(&g->button, edges[i].level, edges[i].t_ns) && *count < max) {
                cu_action a = { .kind = CU_ACT_TOGGLE, .t_ns = edges[i].t_ns };
                acts[(*count)++] = a;
            }
        } else if (ne < MAX_EDGES) {
            enc[ne++] = edges[i];
        }
    }
    int det = cu_quad_feed_edges(&g->quad, enc, ne);
    if (det && *count < max) {
        cu_action a = { .kind = CU_ACT_TURN, .detents = det, .t_ns = g->t_last };
        acts[(*count)++] = a;
    }
}

#ifdef CU_GPIOD_V2
/* ------------------------------------------------------------------ libgpiod v2 */

static struct gpiod_chip *open_chip(const char *spec, char *err, size_t errlen)
{
    char path[300];
    /* v2 opens by path only; accept v1-style names ("gpiochip0") and numbers ("0") as well. */
    if (spec[0] == '/')
        snprintf(path, sizeof path, "%s", spec);
    else if (cu_input_line_offset(spec) >= 0)
        snprintf(path, sizeof path, "/dev/gpiochip%s", spec);
    else
        snprintf(path, sizeof path, "/dev/%s", spec);
    struct gpiod_chip *c = gpiod_chip_open(path);
    if (!c)
        chip_error(spec, errno, err, errlen);
    return c;
}

static int resolve(cu_gpio *g, int i, const char *name, size_t nlines, char *err, size_t errlen)
{
    int off = cu_input_line_offset(name);
    if (off < 0) {
        off = gpiod_chip_get_line_offset_from_name(g->chip, name);
        if (off < 0) {
            snprintf(err, errlen, "gpio: %s has no line named '%s': give an offset or a name from "
                     "`gpioinfo %s`", g->chip_name, name, g->chip_name);
            return 1;
        }
    } else if ((size_t)off >= nlines) {
        snprintf(err, errlen, "gpio: %s has %zu lines, so offset %d does not exist: check --input", g->chip_name,
                 nlines, off);
        return 1;
    }
    g->offset[i] = (unsigned)off;
    snprintf(g->line_name[i], sizeof g->line_name[i], "%s", name);
    struct gpiod_line_info *li = gpiod_chip_get_line_info(g->chip, (unsigned)off);
    if (li) {
        int used = gpiod_line_info_is_used(li);
        int rc = used ? busy_error(g, i, gpiod_line_info_get_consumer(li), err, errlen) : 0;
        gpiod_line_info_free(li);
        if (rc)
            return 1;
    }
    return 0;
}

static struct gpiod_line_request *request(cu_gpio *g, const cu_input_spec *spec, int bias)
{
    struct gpiod_line_settings *enc = gpiod_line_settings_new();
    struct gpiod_line_settings *btn = gpiod_line_settings_new();
    struct gpiod_line_config *lc = gpiod_line_config_new();
    struct gpiod_request_config *rc = gpiod_request_config_new();
    struct gpiod_line_request *req = NULL;
    if (enc && btn && lc && rc) {
        /* Kernel debounce only passes a level stable for the period: it removes contact bounce before it costs
         * an interrupt. Encoders turn fast, so their period is short; the button's can be longer. */
        unsigned long us = spec->debounce_us < 0 ? 1000ul : (unsigned long)spec->debounce_us;
        struct gpiod_line_settings *s[2] = { enc, btn };
        for (int k = 0; k < 2; k++) {
            gpiod_line_settings_set_direction(s[k], GPIOD_LINE_DIRECTION_INPUT);
            gpiod_line_settings_set_edge_detection(s[k], GPIOD_LINE_EDGE_BOTH);
            if (bias)
                gpiod_line_settings_set_bias(s[k], GPIOD_LINE_BIAS_PULL_UP);
            gpiod_line_settings_set_event_clock(s[k], GPIOD_LINE_CLOCK_MONOTONIC);
            gpiod_line_settings_set_debounce_period_us(s[k], k == 0 ? us : (us > 5000 ? us : 5000));
        }
        gpiod_request_config_set_consumer(rc, CONSUMER);
        /* The kernel queues edges while a frame renders (v2 needs no reader thread): a slow frame (a Pi, or the VM
         * under emulation, where a frame takes seconds) must not overflow the queue and lose a detent; the default
         * is 16 per line. 1024 is the kernel's cap (it clamps larger requests). */
        gpiod_request_config_set_event_buffer_size(rc, 1024);
        if (gpiod_line_config_add_line_settings(lc, g->offset, 2, enc) == 0 &&
            (g->nlines < 3 || gpiod_line_config_add_line_settings(lc, &g->offset[LINE_BUTTON], 1, btn) == 0))
            req = gpiod_chip_request_lines(g->chip, rc, lc);
    }
    int e = errno;
    if (rc) gpiod_request_config_free(rc);
    if (lc) gpiod_line_config_free(lc);
    if (btn) gpiod_line_settings_free(btn);
    if (enc) gpiod_line_settings_free(enc);
    errno = e;
    return req;
}

static int level(cu_gpio *g, int i)
{
    return gpiod_line_request_get_value(g->req, g->offset[i]) == GPIOD_LINE_VALUE_ACTIVE;
}

static int open_lines(cu_gpio *g, const cu_input_spec *spec, char *err, size_t errlen)
{
    g->chip = open_chip(spec->chip, err, errlen);
    if (!g->chip)
        return 1;
    struct gpiod_chip_info *info = gpiod_chip_get_info(g->chip);
    size_t nlines = info ? gpiod_chip_info_get_num_lines(info) : 0;
    if (info)
        gpiod_chip_info_free(info);
    const char *names[LINE_COUNT] = { spec->a, spec->b, spec->button };
    for (int i = 0; i < g->nlines; i++)
        if (resolve(g, i, names[i], nlines, err, errlen))
            return 1;
    g->req = request(g, spec, 1);
    if (!g->req && (errno == EINVAL || errno == EOPNOTSUPP)) {
        /* Kernels before 5.5 know no bias flags and some before 5.10 no debounce: retry plain. */
        g->req = request(g, spec, 0);
        if (g->req)
            snprintf(g->note, sizeof g->note, "gpio: %s: this kernel cannot set pull-ups; the encoder needs "
                     "external pull-up resistors", g->chip_name);
    }
    if (!g->req) {
        if (errno == EBUSY)
            return busy_error(g, 0, NULL, err, errlen);
        snprintf(err, errlen, "gpio: requesting lines %s,%s on %s failed: %s", spec->a, spec->b, g->chip_name,
                 strerror(errno));
        return 1;
    }
    g->buf = gpiod_edge_event_buffer_new(64);
    if (!g->buf) {
        snprintf(err, errlen, "gpio: out of memory");
        return 1;
    }
    return 0;
}

int cu_gpio_fds(const cu_gpio *g, int *fds, int max)
{
    if (max < 1)
        return 0;
    fds[0] = gpiod_line_request_get_fd(g->req);
    return 1;
}

static int read_edges(cu_gpio *g, cu_quad_edge *edges, size_t *n, char *err, size_t errlen)
{
    *n = 0;
    while (*n + 64 <= MAX_EDGES) {
        int r = gpiod_line_request_wait_edge_events(g->req, 0);
        if (r == 0)
            return 0;
        if (r > 0)
            r = gpiod_line_request_read_edge_events(g->req, g->buf, 64);
        if (r < 0) {
            snprintf(err, errlen, "gpio: reading %s failed (%s): was the GPIO controller removed? continuing "
                     "without the knob", g->chip_name, strerror(errno));
            return 1;
        }
        for (int k = 0; k < r; k++) {
            struct gpiod_edge_event *ev = gpiod_edge_event_buffer_get_event(g->buf, (unsigned long)k);
            unsigned off = gpiod_edge_event_get_line_offset(ev);
            int line = off == g->offset[LINE_A] ? LINE_A : off == g->offset[LINE_B] ? LINE_B : LINE_BUTTON;
            edges[*n].line = line;
            edges[*n].level = gpiod_edge_event_get_event_type(ev) == GPIOD_EDGE_EVENT_RISING_EDGE;
            edges[*n].t_ns = gpiod_edge_event_get_timestamp_ns(ev);
            (*n)++;
        }
    }
    return 0;
}

static void release(cu_gpio *g)
{
    if (g->buf) gpiod_edge_event_buffer_free(g->buf);
    if (g->req) gpiod_line_request_release(g->req);
    if (g->chip) gpiod_chip_close(g->chip);
}

#else
/* ------------------------------------------------------------------ libgpiod v1 (1.4 .. 1.6) */

static int resolve(cu_gpio *g, int i, const char *name, char *err, size_t errlen)
{
    int off = cu_input_line_offset(name);
    struct gpiod_line *l;
    if (off < 0) {
        l = gpiod_chip_find_line(g->chip, name);
        if (!l) {
            snprintf(err, errlen, "gpio: %s has no line named '%s': give an offset or a name from "
                     "`gpioinfo %s`", g->chip_name, name, g->chip_name);
            return 1;
        }
    } else {
        unsigned nlines = gpiod_chip_num_lines(g->chip);
        if ((unsigned)off >= nlines) {
            snprintf(err, errlen, "gpio: %s has %u lines, so offset %d does not exist: check --input",
                     g->chip_name, nlines, off);
            return 1;
        }
        l = gpiod_chip_get_line(g->chip, (unsigned)off);
        if (!l) {
            snprintf(err, errlen, "gpio: %s line %d: %s", g->chip_name, off, strerror(errno));
            return 1;
        }
    }
    g->line[i] = l;
    g->offset[i] = gpiod_line_offset(l);
    snprintf(g->line_name[i], sizeof g->line_name[i], "%s", name);
    if (gpiod_line_is_used(l))
        return busy_error(g, i, gpiod_line_consumer(l), err, errlen);
    return 0;
}

static int start_reader(cu_gpio *g, char *err, size_t errlen);

static int request(cu_gpio *g, int bias)
{
    struct gpiod_line_request_config cfg = {
        .consumer = CONSUMER,
        .request_type = GPIOD_LINE_REQUEST_EVENT_BOTH_EDGES,
        .flags = bias ? GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP : 0,
    };
    gpiod_line_bulk_init(&g->bulk);
    for (int i = 0; i < g->nlines; i++)
        gpiod_line_bulk_add(&g->bulk, g->line[i]);
    return gpiod_line_request_bulk(&g->bulk, &cfg, NULL);
}

static int level(cu_gpio *g, int i)
{
    return gpiod_line_get_value(g->line[i]) == 1;
}

static int open_lines(cu_gpio *g, const cu_input_spec *spec, char *err, size_t errlen)
{
    /* open_lookup takes a name (gpiochip0), a number, a path or a label, as gpiomon does. */
    g->chip = gpiod_chip_open_lookup(spec->chip);
    if (!g->chip)
        return chip_error(spec->chip, errno ? errno : ENOENT, err, errlen);
    const char *names[LINE_COUNT] = { spec->a, spec->b, spec->button };
    for (int i = 0; i < g->nlines; i++)
        if (resolve(g, i, names[i], err, errlen))
            return 1;
    int rc = request(g, 1);
    if (rc && (errno == EINVAL || errno == EOPNOTSUPP)) {
        rc = request(g, 0); /* kernels before 5.5 have no bias flags */
        if (!rc)
            snprintf(g->note, sizeof g->note, "gpio: %s: this kernel cannot set pull-ups; the encoder needs "
                     "external pull-up resistors", g->chip_name);
    }
    if (rc) {
        if (errno == EBUSY)
            return busy_error(g, 0, NULL, err, errlen);
        snprintf(err, errlen, "gpio: requesting lines %s,%s on %s failed: %s", spec->a, spec->b, g->chip_name,
                 strerror(errno));
        return 1;
    }
    if (spec->debounce_us > 0)
        snprintf(g->note, sizeof g->note, "gpio: libgpiod v1 has no kernel debounce; debounce=%d ignored, the "
                 "decoder rejects bounce itself", spec->debounce_us);
    return start_reader(g, err, errlen);
}

int cu_gpio_fds(const cu_gpio *g, int *fds, int max)
{
    if (max < 1)
        return 0;
    fds[0] = g->wake[0]; /* readable while the reader thread holds edges */
    return 1;
}

static int read_kernel_edges(cu_gpio *g, cu_quad_edge *edges, size_t *n, char *err, size_t errlen)
{
    /* v1 keeps one event queue per line: drain each (poll first, the read would block), then the caller sorts
     * by timestamp to restore the order in which the contacts really moved. */
    *n = 0;
    for (int i = 0; i < g->nlines; i++) {
        struct pollfd p = { .fd = gpiod_line_event_get_fd(g->line[i]), .events = POLLIN };
        while (*n + 16 <= MAX_EDGES && poll(&p, 1, 0) > 0) {
            if (p.revents & (POLLERR | POLLHUP | POLLNVAL)) {
                snprintf(err, errlen, "gpio: %s line %s stopped working (%s): was the GPIO controller removed? "
                         "continuing without the knob", g->chip_name, g->line_name[i],
                         p.revents & POLLNVAL ? "closed" : "error");
                return 1;
            }
            struct gpiod_line_event ev[16];
            int r = gpiod_line_event_read_multiple(g->line[i], ev, 16);
            if (r < 0) {
                if (errno == EAGAIN || errno == EINTR)
                    break;
                snprintf(err, errlen, "gpio: reading %s line %s failed (%s): continuing without the knob",
                         g->chip_name, g->line_name[i], strerror(errno));
                return 1;
            }
            for (int k = 0; k < r; k++) {
                edges[*n].line = i;
                edges[*n].level = ev[k].event_type == GPIOD_LINE_EVENT_RISING_EDGE;
                edges[*n].t_ns = (uint64_t)ev[k].ts.tv_sec * 1000000000u + (uint64_t)ev[k].ts.tv_nsec;
                (*n)++;
            }
            if (r < 16)
                break;
        }
    }
    return 0;
}

/* The reader drains line A's queue, then B's: an A edge that arrives in between would come in the next batch, after
 * a newer B edge of this one. So only edges older than the drain's start (less HOLD_NS, for the kernel's interrupt
 * thread still queueing) go to the main loop; newer ones are held and sorted into the next batch, which comes with
 * the next edge or after HOLD_MS. */
#define HOLD_NS 1000000u
#define HOLD_MS 3

/* Makes the main loop's poll return. A full pipe (EAGAIN) means a wake-up is already pending: nothing to do. */
static void wake_main(cu_gpio *g)
{
    char c = 1;
    if (write(g->wake[1], &c, 1) < 0 && errno != EAGAIN) {
        /* a pipe of our own: no other failure short of a bug */
    }
}

static void *reader_main(void *arg)
{
    cu_gpio *g = arg;
    cu_quad_edge e[2 * MAX_EDGES];
    size_t held = 0;
    for (;;) {
        struct pollfd p[LINE_COUNT + 1];
        int n = 0;
        for (int i = 0; i < g->nlines; i++) {
            p[n].fd = gpiod_line_event_get_fd(g->line[i]);
            p[n++].events = POLLIN;
        }
        p[n].fd = g->stop[0];
        p[n++].events = POLLIN;
        if (poll(p, (nfds_t)n, held ? HOLD_MS : -1) < 0) {
            if (errno == EINTR)
                continue;
            pthread_mutex_lock(&g->mu);
            g->reader_failed = 1;
            snprintf(g->reader_err, sizeof g->reader_err, "gpio: waiting for %s failed (%s): continuing without "
                     "the knob", g->chip_name, strerror(errno));
            pthread_mutex_unlock(&g->mu);
            break;
        }
        if (p[n - 1].revents)
            break; /* cu_gpio_close */
        uint64_t t0 = now_ns();
        size_t ne = 0;
        char err[256];
        int rc = read_kernel_edges(g, e + held, &ne, err, sizeof err);
        ne += held;
        cu_quad_sort_edges(e, ne);
        /* release what is older than the cut; everything when stamps are not on this clock (v1 on kernels before
         * 5.7 stamps with CLOCK_REALTIME), when the hold would overflow, or when the reader stops */
        uint64_t cut = t0 - HOLD_NS;
        size_t out = 0;
        while (out < ne && e[out].t_ns <= cut)
            out++;
        if (rc || ne > MAX_EDGES || (ne && e[ne - 1].t_ns > t0 + 1000000000u))
            out = ne;
        pthread_mutex_lock(&g->mu);
        for (size_t k = 0; k < out; k++) {
            if (g->ring_n < RING_EDGES) /* full: the main loop stalled for minutes; its level sample resynchronises */
                g->ring[g->ring_n++] = e[k];
        }
        if (rc) {
            g->reader_failed = 1;
            snprintf(g->reader_err, sizeof g->reader_err, "%s", err);
        }
        pthread_mutex_unlock(&g->mu);
        held = ne - out;
        memmove(e, e + out, held * sizeof *e);
        if (out || rc)
            wake_main(g);
        if (rc)
            break;
    }
    return NULL;
}

/* The edges the reader thread collected (up to MAX_EDGES; the wake pipe stays readable while more wait). */
static int read_edges(cu_gpio *g, cu_quad_edge *edges, size_t *n, char *err, size_t errlen)
{
    char buf[64];
    while (read(g->wake[0], buf, sizeof buf) > 0) {
    }
    pthread_mutex_lock(&g->mu);
    size_t take = g->ring_n < MAX_EDGES ? g->ring_n : MAX_EDGES;
    memcpy(edges, g->ring, take * sizeof *edges);
    memmove(g->ring, g->ring + take, (g->ring_n - take) * sizeof *edges);
    g->ring_n -= take;
    int failed = g->reader_failed && take == 0;
    if (failed)
        snprintf(err, errlen, "%s", g->reader_err);
    if (g->ring_n)
        wake_main(g);
    pthread_mutex_unlock(&g->mu);
    *n = take;
    return failed;
}

static int start_reader(cu_gpio *g, char *err, size_t errlen)
{
    if (pipe(g->wake) || pipe(g->stop)) {
        snprintf(err, errlen, "gpio: cannot make a pipe: %s", strerror(errno));
        return 1;
    }
    for (int i = 0; i < 2; i++) {
        fcntl(g->wake[i], F_SETFL, O_NONBLOCK);
        fcntl(g->wake[i], F_SETFD, FD_CLOEXEC);
        fcntl(g->stop[i], F_SETFD, FD_CLOEXEC);
    }
    if (pthread_mutex_init(&g->mu, NULL)) {
        snprintf(err, errlen, "gpio: cannot make a mutex");
        return 1;
    }
    g->mu_on = 1;
    int e = pthread_create(&g->reader, NULL, reader_main, g);
    if (e) {
        snprintf(err, errlen, "gpio: cannot start the reader thread: %s", strerror(e));
        return 1;
    }
    g->reader_on = 1;
    return 0;
}

static void release(cu_gpio *g)
{
    if (g->reader_on) {
        char c = 1;
        if (write(g->stop[1], &c, 1) != 1) {
            /* a pipe of our own with nothing in it: cannot fail short of a bug; join would then block */
        }
        pthread_join(g->reader, NULL);
        g->reader_on = 0;
    }
    for (int i = 0; i < 2; i++) {
        if (g->wake[i] >= 0) close(g->wake[i]);
        if (g->stop[i] >= 0) close(g->stop[i]);
        g->wake[i] = g->stop[i] = -1;
    }
    if (g->mu_on) {
        pthread_mutex_destroy(&g->mu);
        g->mu_on = 0;
    }
    if (g->chip) {
        if (g->bulk.num_lines)
            gpiod_line_release_bulk(&g->bulk);
        gpiod_chip_close(g->chip);
    }
}
#endif

int cu_gpio_open(cu_gpio **out, const cu_input_spec *spec, char *err, size_t errlen)
{
    *out = NULL;
    cu_gpio *g = calloc(1, sizeof *g);
    if (!g) {
        snprintf(err, errlen, "gpio: out of memory");
        return 1;
    }
    snprintf(g->chip_name, sizeof g->chip_name, "%s", spec->chip);
    g->nlines = spec->button[0] ? 3 : 2;
#ifndef CU_GPIOD_V2
    g->wake[0] = g->wake[1] = g->stop[0] = g->stop[1] = -1; /* release() closes only what was opened */
#endif
    errno = 0;
    if (open_lines(g, spec, err, errlen)) {
        release(g);
        free(g);
        return 1;
    }
    /* The knob rests in a detent now; its levels define the rest state. The button is up. */
    cu_quad_config qc = { .steps_per_detent = spec->steps_per_detent };
    cu_quad_init(&g->quad, &qc, level(g, LINE_A), level(g, LINE_B));
    cu_button_init(&g->button, 0, g->nlines > 2 ? level(g, LINE_BUTTON) : 1);
    *out = g;
    return 0;
}

int cu_gpio_read(cu_gpio *g, cu_action *acts, int max, int *n, char *err, size_t errlen)
{
    cu_quad_edge edges[MAX_EDGES + 2];
    size_t ne;
    *n = 0;
    if (read_edges(g, edges, &ne, err, errlen))
        return 1;
    if (ne == 0)
        return 0;
    /* Then the levels as they are now: if the kernel lost an edge (queue overflow), this sample shows the state
     * the events missed, and the decoder treats the jump as a missed edge. Edges still queued arrive later with
     * levels already seen and change nothing. */
    uint64_t t = now_ns();
    uint64_t last = 0;
    for (size_t i = 0; i < ne; i++)
        if (edges[i].t_ns > last)
            last = edges[i].t_ns;
    if (t < last)
        t = last; /* v1 on kernels before 5.7 stamps with CLOCK_REALTIME */
    int a = level(g, LINE_A), b = level(g, LINE_B);
    /* If more edges queued meanwhile, the levels are newer than them: skip the sample rather than feed it
     * ahead of older events. */
    struct pollfd p[LINE_COUNT];
    int fds[LINE_COUNT];
    int nfd = cu_gpio_fds(g, fds, LINE_COUNT);
    for (int i = 0; i < nfd; i++) {
        p[i].fd = fds[i];
        p[i].events = POLLIN;
    }
    if (poll(p, (nfds_t)nfd, 0) == 0) {
        edges[ne].line = LINE_A;
        edges[ne].level = a;
        edges[ne].t_ns = t;
        edges[ne + 1].line = LINE_B;
        edges[ne + 1].level = b;
        edges[ne + 1].t_ns = t;
        ne += 2;
    }
    decode(g, edges, ne, acts, max, n);
    return 0;
}

void cu_gpio_close(cu_gpio *g)
{
    if (!g)
        return;
    release(g);
    free(g);
}
