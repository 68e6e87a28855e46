/* platform/input/gpio_v2.c: the knob's libgpiod glue for the v2 API (libgpiod 2.x): one line request for A, B and the
 * button, kernel debounce, and a kernel event queue deep enough that no reader thread is needed. */
#include "gpio.h"
#include "gpio_io.h"
#include <errno.h>
#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char cu_gpio_api_name[] = "libgpiod v2";
const char *cu_gpio_api(void) { return cu_gpio_api_name; }

struct cu_gpio_io {
    struct gpiod_chip *chip;
    struct gpiod_line_request *req;
    struct gpiod_edge_event_buffer *buf;
};

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
        cu_gpio_chip_error(spec, errno, err, errlen);
    return c;
}

static int resolve(cu_gpio *g, int i, const char *name, size_t nlines, char *err, size_t errlen)
{
    int off = cu_input_line_offset(name);
    if (off < 0) {
        off = gpiod_chip_get_line_offset_from_name(g->io->chip, name);
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
    struct gpiod_line_info *li = gpiod_chip_get_line_info(g->io->chip, (unsigned)off);
    if (li) {
        int used = gpiod_line_info_is_used(li);
        int rc = used ? cu_gpio_busy_error(g, i, gpiod_line_info_get_consumer(li), err, errlen) : 0;
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
        gpiod_request_config_set_consumer(rc, CU_GPIO_CONSUMER);
        /* The kernel queues edges while a frame renders (v2 needs no reader thread): a slow frame (a Pi, or the VM
         * under emulation, where a frame takes seconds) must not overflow the queue and lose a detent; the default
         * is 16 per line. 1024 is the kernel's cap (it clamps larger requests). */
        gpiod_request_config_set_event_buffer_size(rc, 1024);
        if (gpiod_line_config_add_line_settings(lc, g->offset, 2, enc) == 0 &&
            (g->nlines < 3 || gpiod_line_config_add_line_settings(lc, &g->offset[CU_GPIO_BUTTON], 1, btn) == 0))
            req = gpiod_chip_request_lines(g->io->chip, rc, lc);
    }
    int e = errno;
    if (rc) gpiod_request_config_free(rc);
    if (lc) gpiod_line_config_free(lc);
    if (btn) gpiod_line_settings_free(btn);
    if (enc) gpiod_line_settings_free(enc);
    errno = e;
    return req;
}

int cu_gpio_io_level(cu_gpio *g, int i)
{
    return gpiod_line_request_get_value(g->io->req, g->offset[i]) == GPIOD_LINE_VALUE_ACTIVE;
}

int cu_gpio_io_open(cu_gpio *g, const cu_input_spec *spec, char *err, size_t errlen)
{
    g->io = calloc(1, sizeof *g->io);
    if (!g->io) {
        snprintf(err, errlen, "gpio: out of memory");
        return 1;
    }
    errno = 0;
    g->io->chip = open_chip(spec->chip, err, errlen);
    if (!g->io->chip)
        return 1;
    struct gpiod_chip_info *info = gpiod_chip_get_info(g->io->chip);
    size_t nlines = info ? gpiod_chip_info_get_num_lines(info) : 0;
    if (info)
        gpiod_chip_info_free(info);
    const char *names[CU_GPIO_LINES] = { spec->a, spec->b, spec->button };
    for (int i = 0; i < g->nlines; i++)
        if (resolve(g, i, names[i], nlines, err, errlen))
            return 1;
    g->io->req = request(g, spec, 1);
    if (!g->io->req && (errno == EINVAL || errno == EOPNOTSUPP)) {
        /* Kernels before 5.5 know no bias flags and some before 5.10 no debounce: retry plain. */
        g->io->req = request(g, spec, 0);
        if (g->io->req)
            snprintf(g->note, sizeof g->note, "gpio: %s: this kernel cannot set pull-ups; the encoder needs "
                     "external pull-up resistors", g->chip_name);
    }
    if (!g->io->req) {
        if (errno == EBUSY)
            return cu_gpio_busy_error(g, 0, NULL, err, errlen);
        snprintf(err, errlen, "gpio: requesting lines %s,%s on %s failed: %s", spec->a, spec->b, g->chip_name,
                 strerror(errno));
        return 1;
    }
    g->io->buf = gpiod_edge_event_buffer_new(64);
    if (!g->io->buf) {
        snprintf(err, errlen, "gpio: out of memory");
        return 1;
    }
    return 0;
}

int cu_gpio_fds(const cu_gpio *g, int *fds, int max)
{
    if (max < 1)
        return 0;
    fds[0] = gpiod_line_request_get_fd(g->io->req);
    return 1;
}

int cu_gpio_io_read(cu_gpio *g, cu_quad_edge *edges, size_t *n, char *err, size_t errlen)
{
    *n = 0;
    while (*n + 64 <= CU_GPIO_MAX_EDGES) {
        int r = gpiod_line_request_wait_edge_events(g->io->req, 0);
        if (r == 0)
            return 0;
        if (r > 0)
            r = gpiod_line_request_read_edge_events(g->io->req, g->io->buf, 64);
        if (r < 0) {
            snprintf(err, errlen, "gpio: reading %s failed (%s): was the GPIO controller removed? continuing "
                     "without the knob", g->chip_name, strerror(errno));
            return 1;
        }
        for (int k = 0; k < r; k++) {
            struct gpiod_edge_event *ev = gpiod_edge_event_buffer_get_event(g->io->buf, (unsigned long)k);
            unsigned off = gpiod_edge_event_get_line_offset(ev);
            edges[*n].line = off == g->offset[CU_GPIO_A]   ? CU_GPIO_A
                             : off == g->offset[CU_GPIO_B] ? CU_GPIO_B
                                                           : CU_GPIO_BUTTON;
            edges[*n].level = gpiod_edge_event_get_event_type(ev) == GPIOD_EDGE_EVENT_RISING_EDGE;
            edges[*n].t_ns = gpiod_edge_event_get_timestamp_ns(ev);
            (*n)++;
        }
    }
    return 0;
}

void cu_gpio_io_close(cu_gpio *g)
{
    if (!g->io)
        return;
    if (g->io->buf) gpiod_edge_event_buffer_free(g->io->buf);
    if (g->io->req) gpiod_line_request_release(g->io->req);
    if (g->io->chip) gpiod_chip_close(g->io->chip);
    free(g->io);
    g->io = NULL;
}

