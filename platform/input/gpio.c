/* platform/input/gpio.c: the rotary encoder and button as a sun control, whichever libgpiod API the build uses: edges in
 * timestamp order through the quadrature decoder, a level sample to resynchronise after lost edges, the one-line
 * errors, and the "gpio" input back end. The libgpiod calls are in gpio_v1.c or gpio_v2.c (see gpio_io.h). */
#include "gpio.h"
#include "gpio_io.h"
#include "input_backend.h"
#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

const char *cu_gpio_note(const cu_gpio *g) { return g->note; }

/* Feeds sorted-or-not edges of A/B/button (line index, level, time) and emits actions. */
static void decode(cu_gpio *g, cu_quad_edge *edges, size_t n, cu_action *acts, int max, int *count)
{
    cu_quad_edge enc[CU_GPIO_MAX_EDGES];
    size_t ne = 0;
    cu_quad_sort_edges(edges, n);
    for (size_t i = 0; i < n; i++) {
        if (edges[i].t_ns > g->t_last)
            g->t_last = edges[i].t_ns;
        if (edges[i].line == CU_GPIO_BUTTON) {
            if (cu_button_feed(&g->button, edges[i].level, edges[i].t_ns) && *count < max) {
                cu_action a = { .kind = CU_ACT_TOGGLE, .t_ns = edges[i].t_ns };
                acts[(*count)++] = a;
            }
        } else if (ne < CU_GPIO_MAX_EDGES) {
            enc[ne++] = edges[i];
        }
    }
    int det = cu_quad_feed_edges(&g->quad, enc, ne);
    if (det && *count < max) {
        cu_action a = { .kind = CU_ACT_TURN, .detents = det, .t_ns = g->t_last };
        acts[(*count)++] = a;
    }
}

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
    if (cu_gpio_io_open(g, spec, err, errlen)) {
        cu_gpio_io_close(g);
        free(g);
        return 1;
    }
    /* The knob rests in a detent now; its levels define the rest state. The button is up. */
    cu_quad_config qc = { .steps_per_detent = spec->steps_per_detent };
    cu_quad_init(&g->quad, &qc, cu_gpio_io_level(g, CU_GPIO_A), cu_gpio_io_level(g, CU_GPIO_B));
    cu_button_init(&g->button, 0, g->nlines > 2 ? cu_gpio_io_level(g, CU_GPIO_BUTTON) : 1);
    *out = g;
    return 0;
}

int cu_gpio_read(cu_gpio *g, cu_action *acts, int max, int *n, char *err, size_t errlen)
{
    cu_quad_edge edges[CU_GPIO_MAX_EDGES + 2];
    size_t ne;
    *n = 0;
    if (cu_gpio_io_read(g, edges, &ne, err, errlen))
        return 1;
    if (ne == 0)
        return 0;
    /* Then the levels as they are now: if the kernel lost an edge (queue overflow), this sample shows the state
     * the events missed, and the decoder treats the jump as a missed edge. Edges still queued arrive later with
     * levels already seen and change nothing. */
    uint64_t t = cu_gpio_now_ns();
    uint64_t last = 0;
    for (size_t i = 0; i < ne; i++)
        if (edges[i].t_ns > last)
            last = edges[i].t_ns;
    if (t < last)
        t = last; /* v1 on kernels before 5.7 stamps with CLOCK_REALTIME */
    int a = cu_gpio_io_level(g, CU_GPIO_A), b = cu_gpio_io_level(g, CU_GPIO_B);
    /* If more edges queued meanwhile, the levels are newer than them: skip the sample rather than feed it
     * ahead of older events. */
    struct pollfd p[CU_GPIO_LINES];
    int fds[CU_GPIO_LINES];
    int nfd = cu_gpio_fds(g, fds, CU_GPIO_LINES);
    for (int i = 0; i < nfd; i++) {
        p[i].fd = fds[i];
        p[i].events = POLLIN;
    }
    if (poll(p, (nfds_t)nfd, 0) == 0) {
        edges[ne].line = CU_GPIO_A;
        edges[ne].level = a;
        edges[ne].t_ns = t;
        edges[ne + 1].line = CU_GPIO_B;
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
    cu_gpio_io_close(g);
    free(g);
}

/* ------------------------------------------------------------------ the "gpio" input back end */

struct cu_input {
    cu_gpio *knob;
};

static int gpio_open(cu_input **out, const cu_input_spec *spec, const cu_input_opts *opts, char *msg, size_t len)
{
    (void)opts;
    cu_input *in = calloc(1, sizeof *in);
    if (!in) {
        snprintf(msg, len, "gpio: out of memory");
        return 1;
    }
    if (cu_gpio_open(&in->knob, spec, msg, len)) {
        free(in);
        return 1;
    }
    char desc[300];
    cu_input_describe(spec, desc, sizeof desc);
    const char *note = cu_gpio_note(in->knob);
    snprintf(msg, len, "%s%sinput: %s (%s)", note, note[0] ? "\n" : "", desc, cu_gpio_api());
    *out = in;
    return 0;
}

static int gpio_fds(cu_input *in, int *fds, int max)
{
    return cu_gpio_fds(in->knob, fds, max);
}

static cu_input_status gpio_read(cu_input *in, cu_action *acts, int max, int *n, char *err, size_t errlen)
{
    return cu_gpio_read(in->knob, acts, max, n, err, errlen) ? CU_INPUT_READ_GONE : CU_INPUT_READ_OK;
}

static void gpio_close(cu_input *in)
{
    cu_gpio_close(in->knob);
    free(in);
}

const cu_input_backend cu_input_gpio = {
    .name = "gpio",
    .kind = CU_INPUT_GPIO,
    .lib = cu_gpio_api_name,
    .open = gpio_open,
    .fds = gpio_fds,
    .read = gpio_read,
    .close = gpio_close,
};
