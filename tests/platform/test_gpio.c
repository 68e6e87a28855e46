/* tests/platform/test_gpio.c: the GPIO knob layer (gpio.c) against a scripted fake of libgpiod, built twice: with
 * the v1
 * glue (gpio_v1.c, Debian 12's libgpiod 1.6 header) and with the v2 glue (gpio_v2.c against gpiod_v2/gpiod.h, so the
 * v2 code runs on a machine that only has libgpiod 1.6). Checks the request (consumer, both edges, pull-up, v2
 * debounce), timestamp ordering of edges from several queues, the button, no edge lost while the caller is busy for longer than the kernel's queue
 * lasts (v1: 16 events per line), and the one-line errors for missing/busy chips and lines. */
#define _POSIX_C_SOURCE 200809L
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdbool.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <sys/ioctl.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <cmocka.h>

#define NLINES 32
#define QMAX 1024

#include <gpiod.h> /* v1: the installed libgpiod 1.x header; v2: tests/platform/gpiod_v2/gpiod.h */
#include "gpio.h"

#ifdef CU_FAKE_GPIOD_V2
/* The fake's state behind the v2 API's opaque types. */
struct gpiod_chip { int unused; };
struct gpiod_chip_info { int unused; };
struct gpiod_line_info { unsigned off; };
struct gpiod_line_settings { int dir, edge, bias, clock; unsigned long debounce; };
struct gpiod_line_config { unsigned off[8]; struct gpiod_line_settings s[8]; int n; };
struct gpiod_request_config { char consumer[64]; size_t bufsize; };
struct gpiod_line_request { int unused; };
struct gpiod_edge_event { int type; uint64_t t; unsigned off; };
struct gpiod_edge_event_buffer { struct gpiod_edge_event ev[64]; size_t cap; };
#endif

/* ---- the fake kernel: 32 lines named GPIO0..GPIO31 on gpiochip0, scripted edges ---- */
static struct fake {
    int chip_errno;                 /* opening the chip fails with this */
    int used[NLINES];
    const char *used_by[NLINES];
    int bias_einval;                /* the kernel rejects bias flags (before 5.5) */
    int level[NLINES];
    struct { int line, level; uint64_t t; } q[QMAX];
    int qn, qr[NLINES], qr_all;
    int rd[NLINES], wr[NLINES];     /* v1: one event fd per line; v2: index 0 for the request */
    int requested[NLINES], nreq, released;
    char consumer[64];
    int bias_up, both_edges, clock_mono;
    unsigned long debounce[NLINES];
    size_t bufsize;                 /* v2: the request's event queue (gpiod_request_config_set_event_buffer_size) */
    int dropped;                    /* edges the fake kernel dropped because their queue was full */
} F;

static uint64_t mono_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void fake_reset(void)
{
    memset(&F, 0, sizeof F);
    for (int i = 0; i < NLINES; i++) {
        F.level[i] = 1; /* pulled up */
        F.rd[i] = F.wr[i] = -1;
    }
}

static void open_pipe(int i)
{
    int p[2];
    assert_int_equal(pipe(p), 0);
    F.rd[i] = p[0];
    F.wr[i] = p[1];
}

/* Queues an edge as the kernel would: the line's level changes and its event fd becomes readable; a full queue
 * drops it (v1: a fixed kfifo of 16 events per line; v2: the request's buffer, default 16 x lines). */
static void fake_edge(int line, int level, uint64_t t)
{
#ifdef CU_FAKE_GPIOD_V2
    int qfd = F.rd[0], cap = F.bufsize ? (int)F.bufsize : 16 * F.nreq;
#else
    int qfd = F.rd[line], cap = 16;
#endif
    int unread = 0;
    assert_int_equal(ioctl(qfd, FIONREAD, &unread), 0);
    F.level[line] = level;
    if (unread >= cap) {
        F.dropped++;
        return;
    }
    assert_true(F.qn < QMAX);
    F.q[F.qn].line = line;
    F.q[F.qn].level = level;
    F.q[F.qn].t = t;
    F.qn++;
    F.level[line] = level;
#ifdef CU_FAKE_GPIOD_V2
    int fd = F.wr[0];
#else
    int fd = F.wr[line];
#endif
    assert_int_equal(write(fd, "e", 1), 1);
}

static int parse_line_name(const char *name)
{
    int n;
    char tail;
    if (sscanf(name, "GPIO%d%c", &n, &tail) == 1 && n >= 0 && n < NLINES)
        return n;
    return -1;
}

#ifndef CU_FAKE_GPIOD_V2
/* ---- libgpiod v1 fakes ---- */
struct gpiod_chip { int unused; };
struct gpiod_line { unsigned off; };
static struct gpiod_chip the_chip;
static struct gpiod_line the_lines[NLINES];

struct gpiod_chip *gpiod_chip_open_lookup(const char *d)
{
    if (F.chip_errno) {
        errno = F.chip_errno;
        return NULL;
    }
    if (strcmp(d, "gpiochip0") && strcmp(d, "/dev/gpiochip0") && strcmp(d, "0")) {
        errno = ENOENT;
        return NULL;
    }
    for (unsigned i = 0; i < NLINES; i++)
        the_lines[i].off = i;
    return &the_chip;
}
void gpiod_chip_close(struct gpiod_chip *c) { (void)c; }
unsigned gpiod_chip_num_lines(struct gpiod_chip *c) { (void)c; return NLINES; }
struct gpiod_line *gpiod_chip_get_line(struct gpiod_chip *c, unsigned off)
{
    (void)c;
    return off < NLINES ? &the_lines[off] : NULL;
}
struct gpiod_line *gpiod_chip_find_line(struct gpiod_chip *c, const char *name)
{
    (void)c;
    int n = parse_line_name(name);
    if (n < 0) {
        errno = ENOENT;
        return NULL;
    }
    return &the_lines[n];
}
unsigned gpiod_line_offset(struct gpiod_line *l) { return l->off; }
bool gpiod_line_is_used(struct gpiod_line *l) { return F.used[l->off]; }
const char *gpiod_line_consumer(struct gpiod_line *l) { return F.used_by[l->off]; }
int gpiod_line_request_bulk(struct gpiod_line_bulk *bulk, const struct gpiod_line_request_config *cfg,
                            const int *defaults)
{
    (void)defaults;
    if (F.bias_einval && (cfg->flags & GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP)) {
        errno = EINVAL;
        return -1;
    }
    snprintf(F.consumer, sizeof F.consumer, "%s", cfg->consumer);
    F.bias_up = (cfg->flags & GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP) != 0;
    F.both_edges = cfg->request_type == GPIOD_LINE_REQUEST_EVENT_BOTH_EDGES;
    for (unsigned i = 0; i < bulk->num_lines; i++) {
        unsigned off = bulk->lines[i]->off;
        F.requested[F.nreq++] = (int)off;
        open_pipe((int)off);
    }
    return 0;
}
int gpiod_line_get_value(struct gpiod_line *l) { return F.level[l->off]; }
int gpiod_line_event_get_fd(struct gpiod_line *l) { return F.rd[l->off]; }
int gpiod_line_event_read_multiple(struct gpiod_line *l, struct gpiod_line_event *ev, unsigned n)
{
    char b[64];
    ssize_t r = read(F.rd[l->off], b, n < sizeof b ? n : sizeof b);
    int k = 0;
    for (ssize_t i = 0; i < r; i++) {
        /* This line's next queued edge. */
        while (F.qr[l->off] < F.qn && F.q[F.qr[l->off]].line != (int)l->off)
            F.qr[l->off]++;
        int j = F.qr[l->off]++;
        ev[k].ts.tv_sec = (time_t)(F.q[j].t / 1000000000u);
        ev[k].ts.tv_nsec = (long)(F.q[j].t % 1000000000u);
        ev[k].event_type = F.q[j].level ? GPIOD_LINE_EVENT_RISING_EDGE : GPIOD_LINE_EVENT_FALLING_EDGE;
        k++;
    }
    return k;
}
void gpiod_line_release_bulk(struct gpiod_line_bulk *bulk)
{
    for (unsigned i = 0; i < bulk->num_lines; i++) {
        unsigned off = bulk->lines[i]->off;
        close(F.rd[off]);
        close(F.wr[off]);
        F.rd[off] = F.wr[off] = -1;
    }
    F.released = 1;
}
#else
/* ---- libgpiod v2 fakes ---- */
static struct gpiod_chip the_chip;
static struct gpiod_chip_info the_info;
static struct gpiod_line_request the_req;
struct gpiod_chip *gpiod_chip_open(const char *path)
{
    if (F.chip_errno) {
        errno = F.chip_errno;
        return NULL;
    }
    if (strcmp(path, "/dev/gpiochip0")) {
        errno = ENOENT;
        return NULL;
    }
    return &the_chip;
}
void gpiod_chip_close(struct gpiod_chip *c) { (void)c; }
struct gpiod_chip_info *gpiod_chip_get_info(struct gpiod_chip *c) { (void)c; return &the_info; }
size_t gpiod_chip_info_get_num_lines(struct gpiod_chip_info *i) { (void)i; return NLINES; }
void gpiod_chip_info_free(struct gpiod_chip_info *i) { (void)i; }
static struct gpiod_line_info infos[NLINES];
struct gpiod_line_info *gpiod_chip_get_line_info(struct gpiod_chip *c, unsigned off)
{
    (void)c;
    infos[off].off = off;
    return &infos[off];
}
bool gpiod_line_info_is_used(struct gpiod_line_info *i) { return F.used[i->off]; }
const char *gpiod_line_info_get_consumer(struct gpiod_line_info *i) { return F.used_by[i->off]; }
void gpiod_line_info_free(struct gpiod_line_info *i) { (void)i; }
int gpiod_chip_get_line_offset_from_name(struct gpiod_chip *c, const char *name)
{
    (void)c;
    int n = parse_line_name(name);
    if (n < 0)
        errno = ENOENT;
    return n;
}
static struct gpiod_line_settings settings_pool[8];
static int nsettings;
struct gpiod_line_settings *gpiod_line_settings_new(void)
{
    struct gpiod_line_settings *s = &settings_pool[nsettings++ % 8];
    memset(s, 0, sizeof *s);
    return s;
}
void gpiod_line_settings_free(struct gpiod_line_settings *s) { (void)s; }
int gpiod_line_settings_set_direction(struct gpiod_line_settings *s, enum gpiod_line_direction d)
{ s->dir = d; return 0; }
int gpiod_line_settings_set_edge_detection(struct gpiod_line_settings *s, enum gpiod_line_edge e)
{ s->edge = e; return 0; }
int gpiod_line_settings_set_bias(struct gpiod_line_settings *s, enum gpiod_line_bias b) { s->bias = b; return 0; }
void gpiod_line_settings_set_debounce_period_us(struct gpiod_line_settings *s, unsigned long us) { s->debounce = us; }
int gpiod_line_settings_set_event_clock(struct gpiod_line_settings *s, enum gpiod_line_clock c)
{ s->clock = c; return 0; }
static struct gpiod_line_config the_lc;
struct gpiod_line_config *gpiod_line_config_new(void) { memset(&the_lc, 0, sizeof the_lc); return &the_lc; }
void gpiod_line_config_free(struct gpiod_line_config *c) { (void)c; }
int gpiod_line_config_add_line_settings(struct gpiod_line_config *c, const unsigned *offs, size_t n,
                                        struct gpiod_line_settings *s)
{
    for (size_t i = 0; i < n; i++) {
        c->off[c->n] = offs[i];
        c->s[c->n++] = *s; /* the library copies the settings */
    }
    return 0;
}
static struct gpiod_request_config the_rc;
struct gpiod_request_config *gpiod_request_config_new(void) { memset(&the_rc, 0, sizeof the_rc); return &the_rc; }
void gpiod_request_config_free(struct gpiod_request_config *c) { (void)c; }
void gpiod_request_config_set_consumer(struct gpiod_request_config *c, const char *s)
{ snprintf(c->consumer, sizeof c->consumer, "%s", s); }
void gpiod_request_config_set_event_buffer_size(struct gpiod_request_config *c, size_t n) { c->bufsize = n; }
struct gpiod_line_request *gpiod_chip_request_lines(struct gpiod_chip *c, struct gpiod_request_config *rc,
                                                    struct gpiod_line_config *lc)
{
    (void)c;
    for (int i = 0; i < lc->n; i++) {
        if (F.bias_einval && lc->s[i].bias == GPIOD_LINE_BIAS_PULL_UP) {
            errno = EINVAL;
            return NULL;
        }
        if (F.used[lc->off[i]]) {
            errno = EBUSY;
            return NULL;
        }
    }
    snprintf(F.consumer, sizeof F.consumer, "%s", rc->consumer);
    F.bufsize = rc->bufsize;
    F.bias_up = F.both_edges = F.clock_mono = 1;
    for (int i = 0; i < lc->n; i++) {
        F.requested[F.nreq++] = (int)lc->off[i];
        F.debounce[lc->off[i]] = lc->s[i].debounce;
        F.bias_up &= lc->s[i].bias == GPIOD_LINE_BIAS_PULL_UP;
        F.both_edges &= lc->s[i].edge == GPIOD_LINE_EDGE_BOTH && lc->s[i].dir == GPIOD_LINE_DIRECTION_INPUT;
        F.clock_mono &= lc->s[i].clock == GPIOD_LINE_CLOCK_MONOTONIC;
    }
    open_pipe(0);
    return &the_req;
}
void gpiod_line_request_release(struct gpiod_line_request *r)
{
    (void)r;
    close(F.rd[0]);
    close(F.wr[0]);
    F.released = 1;
}
enum gpiod_line_value gpiod_line_request_get_value(struct gpiod_line_request *r, unsigned off)
{
    (void)r;
    return F.level[off] ? GPIOD_LINE_VALUE_ACTIVE : GPIOD_LINE_VALUE_INACTIVE;
}
int gpiod_line_request_get_fd(struct gpiod_line_request *r) { (void)r; return F.rd[0]; }
int gpiod_line_request_wait_edge_events(struct gpiod_line_request *r, int64_t timeout_ns)
{
    (void)r;
    struct pollfd p = { .fd = F.rd[0], .events = POLLIN };
    return poll(&p, 1, (int)(timeout_ns / 1000000)) > 0;
}
static struct gpiod_edge_event_buffer the_buf;
struct gpiod_edge_event_buffer *gpiod_edge_event_buffer_new(size_t cap) { the_buf.cap = cap; return &the_buf; }
void gpiod_edge_event_buffer_free(struct gpiod_edge_event_buffer *b) { (void)b; }
int gpiod_line_request_read_edge_events(struct gpiod_line_request *r, struct gpiod_edge_event_buffer *b, size_t max)
{
    (void)r;
    char c[64];
    ssize_t n = read(F.rd[0], c, max < sizeof c ? max : sizeof c);
    for (ssize_t i = 0; i < n; i++) {
        int j = F.qr_all++;
        b->ev[i].type = F.q[j].level ? GPIOD_EDGE_EVENT_RISING_EDGE : GPIOD_EDGE_EVENT_FALLING_EDGE;
        b->ev[i].t = F.q[j].t;
        b->ev[i].off = (unsigned)F.q[j].line;
    }
    return (int)n;
}
struct gpiod_edge_event *gpiod_edge_event_buffer_get_event(struct gpiod_edge_event_buffer *b, unsigned long i)
{ return &b->ev[i]; }
enum gpiod_edge_event_type gpiod_edge_event_get_event_type(struct gpiod_edge_event *e) { return e->type; }
uint64_t gpiod_edge_event_get_timestamp_ns(struct gpiod_edge_event *e) { return e->t; }
unsigned gpiod_edge_event_get_line_offset(struct gpiod_edge_event *e) { return e->off; }
#endif

/* ---- tests, the same for both APIs ---- */

static cu_input_spec spec_of(const char *s)
{
    cu_input_spec sp;
    char err[256];
    assert_int_equal(cu_input_parse(s, &sp, err, sizeof err), 0);
    return sp;
}

static int setup(void **state)
{
    (void)state;
    fake_reset();
    return 0;
}

static void test_request(void **state)
{
    (void)state;
    cu_gpio *g;
    char err[512];
    cu_input_spec s = spec_of("gpio:chip=gpiochip0,a=17,b=GPIO27,button=22");
    assert_int_equal(cu_gpio_open(&g, &s, err, sizeof err), 0);
    assert_string_equal(F.consumer, "cumulo");
    assert_int_equal(F.bias_up, 1);
    assert_int_equal(F.both_edges, 1);
    assert_int_equal(F.nreq, 3);
    assert_int_equal(F.requested[0], 17);
    assert_int_equal(F.requested[1], 27);
    assert_int_equal(F.requested[2], 22);
    assert_string_equal(cu_gpio_note(g), "");
#ifdef CU_FAKE_GPIOD_V2
    assert_string_equal(cu_gpio_api(), "libgpiod v2");
    assert_int_equal(F.clock_mono, 1);
    assert_int_equal(F.debounce[17], 1000);  /* kernel debounce on the encoder... */
    assert_int_equal(F.debounce[22], 5000);  /* ...and longer on the button */
#else
    assert_string_equal(cu_gpio_api(), "libgpiod v1");
#endif
    int fds[4];
    assert_int_equal(cu_gpio_fds(g, fds, 4), 1); /* v2: the request's; v1: the reader thread's wake-up pipe */
    cu_gpio_close(g);
    assert_int_equal(F.released, 1);
}

/* Waits up to ms for the knob's fds to become readable; 1 if they did. */
static int wait_readable(cu_gpio *g, int ms)
{
    int fds[4], n = cu_gpio_fds(g, fds, 4);
    struct pollfd p[4];
    for (int i = 0; i < n; i++) {
        p[i].fd = fds[i];
        p[i].events = POLLIN;
    }
    return poll(p, (nfds_t)n, ms) > 0;
}

/* Fifty bouncy detents counter-clockwise while the caller renders a long frame (it does not read for 0.2 s): 600
 * edges, 300 per line, far more than the kernel queues. The VM test lost a detent this way with libgpiod v1 (16
 * events per line) until a reader thread drained the queues as edges came. Every detent must arrive. */
static void test_busy_caller_loses_no_edge(void **state)
{
    (void)state;
    cu_gpio *g;
    char err[512];
    cu_input_spec s = spec_of("gpio:a=GPIO5,b=6");
    assert_int_equal(cu_gpio_open(&g, &s, err, sizeof err), 0);
    uint64_t t = mono_ns() - 10000000000u;
    const uint64_t step = 8000000u, chatter = 30000u;
    struct timespec pause = {0, 300000}; /* edges come over time, as from a hand: 0.2 s in all */
    for (int d = 0; d < 50; d++) {
        const int line[4] = {6, 5, 6, 5}, to[4] = {0, 0, 1, 1};
        for (int k = 0; k < 4; k++) {
            fake_edge(line[k], to[k], t += step);
            fake_edge(line[k], !to[k], t += chatter); /* the contact bounces back and settles */
            fake_edge(line[k], to[k], t += chatter);
            nanosleep(&pause, NULL);
        }
    }
    int turned = 0, rounds = 0;
    while (wait_readable(g, 200) && rounds++ < 100) {
        cu_action acts[16];
        int n;
        assert_int_equal(cu_gpio_read(g, acts, 16, &n, err, sizeof err), 0);
        for (int i = 0; i < n; i++)
            if (acts[i].kind == CU_ACT_TURN)
                turned += acts[i].detents;
    }
    printf("busy caller: %d detents of -50, %d edges dropped by the fake kernel\n", turned, F.dropped);
    assert_int_equal(turned, -50);
    cu_gpio_close(g);
}

/* Two detents clockwise, a bounce on the first edge, the button pressed with bounce, one detent back. Edges of
 * different lines interleave in time; v1 reads them per line, so only the timestamp sort restores the order. */
static void test_turns_and_button(void **state)
{
    (void)state;
    cu_gpio *g;
    char err[512];
    cu_input_spec s = spec_of("gpio:a=GPIO5,b=6,button=13");
    assert_int_equal(cu_gpio_open(&g, &s, err, sizeof err), 0);
    uint64_t t = mono_ns() - 2000000000u;
    const uint64_t step = 8000000u;
    for (int d = 0; d < 2; d++) {
        fake_edge(5, 0, t += step);
        if (d == 0) {
            fake_edge(5, 1, t += 30000);
            fake_edge(5, 0, t += 30000);
        }
        fake_edge(6, 0, t += step);
        fake_edge(5, 1, t += step);
        fake_edge(6, 1, t += step);
    }
    fake_edge(13, 0, t += step);
    fake_edge(13, 1, t += 200000);
    fake_edge(13, 0, t += 200000);
    fake_edge(13, 1, t += 150000000u);
    fake_edge(6, 0, t += step);
    fake_edge(5, 0, t += step);
    fake_edge(6, 1, t += step);
    fake_edge(5, 1, t += step);

    cu_action acts[16];
    int n, turned = 0, toggles = 0;
    for (int round = 0; round < 4; round++) {
        wait_readable(g, 200); /* as the run loop polls (v1: the reader thread hands the edges over) */
        assert_int_equal(cu_gpio_read(g, acts, 16, &n, err, sizeof err), 0);
        for (int i = 0; i < n; i++) {
            if (acts[i].kind == CU_ACT_TURN)
                turned += acts[i].detents;
            else if (acts[i].kind == CU_ACT_TOGGLE)
                toggles++;
            else
                fail_msg("unexpected action %d", acts[i].kind);
        }
    }
    assert_int_equal(turned, 1);
    assert_int_equal(toggles, 1);
    /* Nothing pending: a read returns at once with no actions. */
    assert_int_equal(cu_gpio_read(g, acts, 16, &n, err, sizeof err), 0);
    assert_int_equal(n, 0);
    cu_gpio_close(g);
}

static void expect_open_error(const char *spec, const char *fragment)
{
    cu_gpio *g = (cu_gpio *)1;
    char err[512] = "";
    cu_input_spec s = spec_of(spec);
    assert_int_not_equal(cu_gpio_open(&g, &s, err, sizeof err), 0);
    assert_null(g);
    if (!strstr(err, fragment))
        fail_msg("'%s': message '%s' lacks '%s'", spec, err, fragment);
    assert_non_null(strstr(err, "gpio: "));
}

static void test_errors(void **state)
{
    (void)state;
    expect_open_error("gpio:chip=gpiochip9,a=1,b=2", "no GPIO chip 'gpiochip9' on this machine");
    F.chip_errno = EACCES;
    expect_open_error("gpio:a=1,b=2", "permission denied: add the user to group 'gpio'");
    F.chip_errno = 0;
    expect_open_error("gpio:a=ENC_A,b=2", "gpiochip0 has no line named 'ENC_A'");
    expect_open_error("gpio:a=1,b=40", "gpiochip0 has 32 lines, so offset 40 does not exist");
    F.used[8] = 1;
    F.used_by[8] = "spi0 CS0";
    expect_open_error("gpio:a=7,b=8", "line 8 (offset 8) on gpiochip0 is busy (used by 'spi0 CS0')");
}

static void test_kernel_without_bias(void **state)
{
    (void)state;
    F.bias_einval = 1;
    cu_gpio *g;
    char err[512];
    cu_input_spec s = spec_of("gpio:a=1,b=2");
    assert_int_equal(cu_gpio_open(&g, &s, err, sizeof err), 0);
    assert_non_null(strstr(cu_gpio_note(g), "external pull-up resistors"));
    assert_int_equal(F.bias_up, 0);
    cu_gpio_close(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_request, setup),
        cmocka_unit_test_setup(test_turns_and_button, setup),
        cmocka_unit_test_setup(test_busy_caller_loses_no_edge, setup),
        cmocka_unit_test_setup(test_errors, setup),
        cmocka_unit_test_setup(test_kernel_without_bias, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
