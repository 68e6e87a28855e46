/* platform/input/gpio_v1.c: the knob's libgpiod glue for the v1 API (libgpiod 1.4 .. 1.6, Debian 12): lines
 * requested in bulk, one kernel event queue per line, and a reader thread that drains those queues as edges come. */
#include "gpio.h"
#include "gpio_io.h"
#include <errno.h>
#include <fcntl.h>
#include <gpiod.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define RING_EDGES 4096 /* edges the reader thread holds for the main loop (minutes of turning at frame rate) */

const char cu_gpio_api_name[] = "libgpiod v1";
const char *cu_gpio_api(void) { return cu_gpio_api_name; }

struct cu_gpio_io {
    struct gpiod_chip *chip;
    struct gpiod_line *line[CU_GPIO_LINES];
    struct gpiod_line_bulk bulk;
    /* The v1 uAPI queues 16 events per line in the kernel, fixed: a frame that takes longer than a few detents
     * overflows it and loses detents. A reader thread moves edges from the kernel into `ring` as they come;
     * `wake` tells the main loop's poll that edges wait. */
    pthread_t reader;
    int reader_on;
    int wake[2], stop[2];   /* pipes: reader -> main loop (edges queued), main -> reader (quit) */
    pthread_mutex_t mu;     /* guards ring, ring_n, reader_failed, reader_err */
    int mu_on;
    cu_quad_edge ring[RING_EDGES];
    size_t ring_n;
    int reader_failed;
    char reader_err[256];
};

static int resolve(cu_gpio *g, int i, const char *name, char *err, size_t errlen)
{
    cu_gpio_io *io = g->io;
    int off = cu_input_line_offset(name);
    struct gpiod_line *l;
    if (off < 0) {
        l = gpiod_chip_find_line(io->chip, name);
        if (!l) {
            snprintf(err, errlen, "gpio: %s has no line named '%s': give an offset or a name from "
                     "`gpioinfo %s`", g->chip_name, name, g->chip_name);
            return 1;
        }
    } else {
        unsigned nlines = gpiod_chip_num_lines(io->chip);
        if ((unsigned)off >= nlines) {
            snprintf(err, errlen, "gpio: %s has %u lines, so offset %d does not exist: check --input",
                     g->chip_name, nlines, off);
            return 1;
        }
        l = gpiod_chip_get_line(io->chip, (unsigned)off);
        if (!l) {
            snprintf(err, errlen, "gpio: %s line %d: %s", g->chip_name, off, strerror(errno));
            return 1;
        }
    }
    io->line[i] = l;
    g->offset[i] = gpiod_line_offset(l);
    snprintf(g->line_name[i], sizeof g->line_name[i], "%s", name);
    if (gpiod_line_is_used(l))
        return cu_gpio_busy_error(g, i, gpiod_line_consumer(l), err, errlen);
    return 0;
}

static int start_reader(cu_gpio *g, char *err, size_t errlen);

static int request(cu_gpio *g, int bias)
{
    cu_gpio_io *io = g->io;
    struct gpiod_line_request_config cfg = {
        .consumer = CU_GPIO_CONSUMER,
        .request_type = GPIOD_LINE_REQUEST_EVENT_BOTH_EDGES,
        .flags = bias ? GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP : 0,
    };
    gpiod_line_bulk_init(&io->bulk);
    for (int i = 0; i < g->nlines; i++)
        gpiod_line_bulk_add(&io->bulk, io->line[i]);
    return gpiod_line_request_bulk(&io->bulk, &cfg, NULL);
}

int cu_gpio_io_level(cu_gpio *g, int i)
{
    return gpiod_line_get_value(g->io->line[i]) == 1;
}

int cu_gpio_io_open(cu_gpio *g, const cu_input_spec *spec, char *err, size_t errlen)
{
    cu_gpio_io *io = g->io = calloc(1, sizeof *g->io);
    if (!io) {
        snprintf(err, errlen, "gpio: out of memory");
        return 1;
    }
    io->wake[0] = io->wake[1] = io->stop[0] = io->stop[1] = -1; /* close() shuts only what was opened */
    errno = 0;
    /* open_lookup takes a name (gpiochip0), a number, a path or a label, as gpiomon does. */
    io->chip = gpiod_chip_open_lookup(spec->chip);
    if (!io->chip)
        return cu_gpio_chip_error(spec->chip, errno ? errno : ENOENT, err, errlen);
    const char *names[CU_GPIO_LINES] = { spec->a, spec->b, spec->button };
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
            return cu_gpio_busy_error(g, 0, NULL, err, errlen);
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
    fds[0] = g->io->wake[0]; /* readable while the reader thread holds edges */
    return 1;
}

static int read_kernel_edges(cu_gpio *g, cu_quad_edge *edges, size_t *n, char *err, size_t errlen)
{
    cu_gpio_io *io = g->io;
    /* v1 keeps one event queue per line: drain each (poll first, the read would block), then the caller sorts
     * by timestamp to restore the order in which the contacts really moved. */
    *n = 0;
    for (int i = 0; i < g->nlines; i++) {
        struct pollfd p = { .fd = gpiod_line_event_get_fd(io->line[i]), .events = POLLIN };
        while (*n + 16 <= CU_GPIO_MAX_EDGES && poll(&p, 1, 0) > 0) {
            if (p.revents & (POLLERR | POLLHUP | POLLNVAL)) {
                snprintf(err, errlen, "gpio: %s line %s stopped working (%s): was the GPIO controller removed? "
                         "continuing without the knob", g->chip_name, g->line_name[i],
                         p.revents & POLLNVAL ? "closed" : "error");
                return 1;
            }
            struct gpiod_line_event ev[16];
            int r = gpiod_line_event_read_multiple(io->line[i], ev, 16);
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
    if (write(g->io->wake[1], &c, 1) < 0 && errno != EAGAIN) {
        /* a pipe of our own: no other failure short of a bug */
    }
}

static void *reader_main(void *arg)
{
    cu_gpio *g = arg;
    cu_gpio_io *io = g->io;
    cu_quad_edge e[2 * CU_GPIO_MAX_EDGES];
    size_t held = 0;
    for (;;) {
        struct pollfd p[CU_GPIO_LINES + 1];
        int n = 0;
        for (int i = 0; i < g->nlines; i++) {
            p[n].fd = gpiod_line_event_get_fd(io->line[i]);
            p[n++].events = POLLIN;
        }
        p[n].fd = io->stop[0];
        p[n++].events = POLLIN;
        if (poll(p, (nfds_t)n, held ? HOLD_MS : -1) < 0) {
            if (errno == EINTR)
                continue;
            pthread_mutex_lock(&io->mu);
            io->reader_failed = 1;
            snprintf(io->reader_err, sizeof io->reader_err, "gpio: waiting for %s failed (%s): continuing without "
                     "the knob", g->chip_name, strerror(errno));
            pthread_mutex_unlock(&io->mu);
            break;
        }
        if (p[n - 1].revents)
            break; /* cu_gpio_close */
        uint64_t t0 = cu_gpio_now_ns();
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
        if (rc || ne > CU_GPIO_MAX_EDGES || (ne && e[ne - 1].t_ns > t0 + 1000000000u))
            out = ne;
        pthread_mutex_lock(&io->mu);
        for (size_t k = 0; k < out; k++) {
            if (io->ring_n < RING_EDGES) /* full: the main loop stalled for minutes; its level sample resynchronises */
                io->ring[io->ring_n++] = e[k];
        }
        if (rc) {
            io->reader_failed = 1;
            snprintf(io->reader_err, sizeof io->reader_err, "%s", err);
        }
        pthread_mutex_unlock(&io->mu);
        held = ne - out;
        memmove(e, e + out, held * sizeof *e);
        if (out || rc)
            wake_main(g);
        if (rc)
            break;
    }
    return NULL;
}

/* The edges the reader thread collected (up to CU_GPIO_MAX_EDGES; the wake pipe stays readable while more wait). */
int cu_gpio_io_read(cu_gpio *g, cu_quad_edge *edges, size_t *n, char *err, size_t errlen)
{
    cu_gpio_io *io = g->io;
    char buf[64];
    while (read(io->wake[0], buf, sizeof buf) > 0) {
    }
    pthread_mutex_lock(&io->mu);
    size_t take = io->ring_n < CU_GPIO_MAX_EDGES ? io->ring_n : CU_GPIO_MAX_EDGES;
    memcpy(edges, io->ring, take * sizeof *edges);
    memmove(io->ring, io->ring + take, (io->ring_n - take) * sizeof *edges);
    io->ring_n -= take;
    int failed = io->reader_failed && take == 0;
    if (failed)
        snprintf(err, errlen, "%s", io->reader_err);
    if (io->ring_n)
        wake_main(g);
    pthread_mutex_unlock(&io->mu);
    *n = take;
    return failed;
}

static int start_reader(cu_gpio *g, char *err, size_t errlen)
{
    cu_gpio_io *io = g->io;
    if (pipe(io->wake) || pipe(io->stop)) {
        snprintf(err, errlen, "gpio: cannot make a pipe: %s", strerror(errno));
        return 1;
    }
    for (int i = 0; i < 2; i++) {
        fcntl(io->wake[i], F_SETFL, O_NONBLOCK);
        fcntl(io->wake[i], F_SETFD, FD_CLOEXEC);
        fcntl(io->stop[i], F_SETFD, FD_CLOEXEC);
    }
    if (pthread_mutex_init(&io->mu, NULL)) {
        snprintf(err, errlen, "gpio: cannot make a mutex");
        return 1;
    }
    io->mu_on = 1;
    int e = pthread_create(&io->reader, NULL, reader_main, g);
    if (e) {
        snprintf(err, errlen, "gpio: cannot start the reader thread: %s", strerror(e));
        return 1;
    }
    io->reader_on = 1;
    return 0;
}

void cu_gpio_io_close(cu_gpio *g)
{
    cu_gpio_io *io = g->io;
    if (!io)
        return;
    if (io->reader_on) {
        char c = 1;
        if (write(io->stop[1], &c, 1) != 1) {
            /* a pipe of our own with nothing in it: cannot fail short of a bug; join would then block */
        }
        pthread_join(io->reader, NULL);
    }
    for (int i = 0; i < 2; i++) {
        if (io->wake[i] >= 0) close(io->wake[i]);
        if (io->stop[i] >= 0) close(io->stop[i]);
    }
    if (io->mu_on)
        pthread_mutex_destroy(&io->mu);
    if (io->chip) {
        if (io->bulk.num_lines)
            gpiod_line_release_bulk(&io->bulk);
        gpiod_chip_close(io->chip);
    }
    free(io);
    g->io = NULL;
}
