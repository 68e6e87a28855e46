/* app/cmd_ig.c: `cumulo ig` — cumulo as a flight simulator's image generator: a host drives the eyepoint, the view's
 * frustum, the date and time (the sun) and the cloud layers over CIGI 3.3, FlightGear's generic protocol or X-Plane's
 * UDP datarefs; each frame is drawn when the host's data for it has arrived, and CIGI gets its Start of Frame. */
#include "commands.h"
#include "ig_world.h"
#include "session.h"
#include "sim_link.h"
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define LATENCY_KEEP 4096 /* the latest latencies the report's median and 95th percentile come from */

static volatile sig_atomic_t quit_signal;
static void on_signal(int sig) { quit_signal = sig; }

typedef struct ig_args {
    cli_opts o;
    cu_sim_link_spec link;
    long frames_max;
    double frame_timeout;     /* s: a frame is drawn anyway when the host says nothing for this long */
    double extent;            /* m: the host's layers' squares */
    const char *save_dir;     /* --save: every frame as DIR/frame_NNNNNN.png */
    const char *dump_scene;   /* --dump-scene: the scene drawn last, written at the end */
    int trace;                /* --trace: one line per frame on stdout */
} ig_args;

static void usage(FILE *f)
{
    fprintf(f,
        "usage: cumulo ig SCENE [--input SPEC] [--frames N] [--frame-timeout S] [--layer-extent M] [--save DIR]\n"
        "                 [--trace] [--dump-scene FILE] [--platform drm|x11|wayland|headless] [--size WxH]\n"
        "                 [--set S.K=V]... [-v]\n"
        "  Draws SCENE as a simulator's image generator: the host moves the eyepoint, sets the date and time (the sun\n"
        "  at the eyepoint) and the cloud layers. Geodetic positions are WGS84 about the scene's database origin\n"
        "  ([scene] origin_latitude, origin_longitude, origin_altitude).\n"
        "  --input cigi:[ADDR:]PORT[,host=HOST:PORT][,view=N][,entity=N]   CIGI 3.3 host (default cigi:8004): IG\n"
        "                      Control, Entity Control (the ownship, entity 0), View Control and View Definition\n"
        "                      (view 0), Celestial Sphere, Atmosphere and Weather Control (cloud layers 1-3); Start\n"
        "                      of Frame goes to host=, else to the sender of the host's datagrams\n"
        "  --input fg:[ADDR:]PORT   FlightGear: fgfs --generic=socket,out,30,HOST,PORT,udp,cumulo (cumulo.xml)\n"
        "  --input xplane:HOST:PORT[,local=PORT][,freq=HZ][,year=Y]   X-Plane's UDP datarefs (RREF; X-Plane\n"
        "                      listens on 49000); year: X-Plane sends only the day of the year (default: this year)\n"
        "  --frames N          stop after N frames (default: until SIGINT or SIGTERM)\n"
        "  --frame-timeout S   draw a frame anyway after S seconds without the host (0.001..60, default 1)\n"
        "  --layer-extent M    side of the square the host's cloud layers fill about the eye, 1000..200000 m\n"
        "                      (default 20000)\n"
        "  --save DIR          write every frame as DIR/frame_NNNNNN.png\n"
        "  --dump-scene FILE   at the end, write the scene drawn last (the file with the host's layers as [layer]s)\n"
        "  --trace             one line per frame on stdout: frame numbers, eye, sun, layers, latency\n"
        "  --platform, --size, --set, --time, --data-dir, -v   as for cumulo run\n");
}

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

enum { OPT_INPUT = 0x200, OPT_FRAMES, OPT_TIMEOUT, OPT_EXTENT, OPT_SAVE, OPT_TRACE, OPT_DUMP };
static const struct option long_opts[] = {
    CLI_COMMON_LONGOPTS,
    {"input", required_argument, NULL, OPT_INPUT}, {"frames", required_argument, NULL, OPT_FRAMES},
    {"frame-timeout", required_argument, NULL, OPT_TIMEOUT}, {"layer-extent", required_argument, NULL, OPT_EXTENT},
    {"save", required_argument, NULL, OPT_SAVE}, {"trace", no_argument, NULL, OPT_TRACE},
    {"dump-scene", required_argument, NULL, OPT_DUMP},
    {NULL, 0, NULL, 0},
};

static int number(const char *opt, const char *v, double lo, double hi, double *out)
{
    char *end;
    double x = strtod(v, &end);
    if (end == v || *end || !(x >= lo && x <= hi)) {
        fprintf(stderr, "cumulo ig: %s expects a number in %g..%g, got '%s'\n", opt, lo, hi, v);
        return 1;
    }
    *out = x;
    return 0;
}

/* -1 to go on, or the exit status (0 after --help, 2 after a usage error). */
static int parse_args(ig_args *a, int argc, char **argv)
{
    memset(a, 0, sizeof *a);
    a->frame_timeout = 1.0;
    a->extent = 20000;
    char err[300];
    cu_sim_link_parse("cigi:8004", &a->link, err, sizeof err);
    opterr = 0;
    optind = 1;
    for (;;) {
        int at = optind, c = getopt_long(argc, argv, "-:hv", long_opts, NULL);
        if (c == -1 && at == argc)
            break;
        int common = cli_common_getopt(&a->o, c, optarg, "cumulo ig");
        if (common < 0)
            return 2;
        if (common)
            continue;
        switch (c) {
        case 'h': usage(stdout); return 0;
        case CLI_OPT_VERSION: cli_print_version(stdout, "cumulo"); return 0;
        case 1:
            if (a->o.scene_path) {
                fprintf(stderr, "cumulo ig: one scene only ('%s' and '%s')\n", a->o.scene_path, optarg);
                return 2;
            }
            a->o.scene_path = optarg;
            break;
        case OPT_INPUT:
            if (cu_sim_link_parse(optarg, &a->link, err, sizeof err)) {
                fprintf(stderr, "cumulo ig: --input %s\n", err);
                return 2;
            }
            break;
        case OPT_FRAMES:
            if (cli_parse_counts(optarg, 0, 1, 1, 2000000000L, &a->frames_max)) {
                fprintf(stderr, "cumulo ig: --frames expects a whole number in 1..2000000000, got '%s'\n", optarg);
                return 2;
            }
            break;
        case OPT_TIMEOUT:
            if (number("--frame-timeout", optarg, 0.001, 60, &a->frame_timeout))
                return 2;
            break;
        case OPT_EXTENT:
            if (number("--layer-extent", optarg, 1000, 200000, &a->extent))
                return 2;
            break;
        case OPT_SAVE: a->save_dir = optarg; break;
        case OPT_TRACE: a->trace = 1; break;
        case OPT_DUMP: a->dump_scene = optarg; break;
        case ':': fprintf(stderr, "cumulo ig: %s needs a value\n", argv[at]); return 2;
        default:
            fprintf(stderr, "cumulo ig: unknown option '%s'\n", argv[at]);
            usage(stderr);
            return 2;
        }
    }
    if (!a->o.scene_path) {
        usage(stderr);
        return 2;
    }
    return -1;
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* The latency report: median, 95th percentile and the largest of the kept samples, ms. */
static void latency_stats(const double *lat, long n, double *med, double *p95, double *mx)
{
    *med = *p95 = *mx = NAN;
    if (n <= 0)
        return;
    long k = n < LATENCY_KEEP ? n : LATENCY_KEEP;
    double *s = malloc(sizeof *s * (size_t)k);
    if (!s)
        return;
    memcpy(s, lat, sizeof *s * (size_t)k);
    qsort(s, (size_t)k, sizeof *s, cmp_double);
    *med = s[k / 2];
    *p95 = s[(long)floor(0.95 * (double)(k - 1))];
    *mx = s[k - 1];
    free(s);
}

/* Waits until the host's data for a frame has arrived, the timeout passes or a signal comes. */
static void wait_for_frame(cu_sim_link *l, cu_sim_state *st, double timeout)
{
    uint64_t end = now_ns() + (uint64_t)(timeout * 1e9);
    l->frame_ready = 0;
    cu_sim_link_poll(l, st, now_ns());
    while (!l->frame_ready && !quit_signal) {
        uint64_t t = now_ns();
        if (t >= end)
            break;
        struct pollfd p = { .fd = l->fd, .events = POLLIN };
        int ms = (int)((end - t + 999999) / 1000000);
        if (poll(&p, 1, ms) > 0)
            cu_sim_link_poll(l, st, now_ns());
    }
    /* what else came with the frame (CIGI: a host may split a frame over datagrams) */
    cu_sim_link_poll(l, st, now_ns());
}

static int save_frame(cli_session *s, const char *dir, long frame)
{
    uint8_t *px = malloc((size_t)s->width * (size_t)s->height * 4);
    char path[1024];
    snprintf(path, sizeof path, "%s/frame_%06ld.png", dir, frame);
    cu_error e;
    int rc = !px || cli_session_read_rgba8(s, px) || cu_write_png(path, px, s->width, s->height, &e);
    if (rc)
        fprintf(stderr, "cumulo ig: cannot save %s: %s\n", path, px ? e.msg : "out of memory");
    free(px);
    return rc;
}

static void trace_line(const ig_args *a, const cu_sim_link *l, const ig_world *w, const cu_renderer *r, long frame,
                       double lat_ms)
{
    double el, az;
    cu_renderer_get_sun(r, &el, &az);
    printf("ig frame=%ld host_frame=%lu eye=%.3f,%.3f,%.3f fwd=%.6f,%.6f,%.6f up=%.6f,%.6f,%.6f sun=%.4f,%.4f "
           "utc=%s time=%.3f layers=%lu latency_ms=%.3f\n", frame,
           a->link.proto == CU_SIM_CIGI ? (unsigned long)l->cigi.host_frame : 0ul, w->eye[0], w->eye[1], w->eye[2],
           w->fwd[0], w->fwd[1], w->fwd[2], w->up[0], w->up[1], w->up[2], el, az, w->utc[0] ? w->utc : "-",
           cu_renderer_get_time(r), w->rebuilds, lat_ms);
    fflush(stdout);
}

/* The clouds' time. CIGI: the host's timestamp where it gives one (every channel of a multi-channel display then
 * shows the same clouds); the 10 us ticks wrap after 11.9 h, so differences are taken modulo 2^32. A frame without
 * one from a host that gave them keeps the host's time base: the host frame drawn last, again, at its own time (a
 * repeat draws the same picture), a new one at the host's last time plus this IG's clock since then. Never a jump to
 * the IG's own clock and back, which moves every cloud and has their maps made again. Other links, and a CIGI host
 * that never gave a timestamp: this IG's clock. */
typedef struct ig_clock {
    int have_ts;
    uint32_t ts_first;
    double host_t;            /* the clouds' time of the last frame with a timestamp */
    uint64_t host_ns;         /* this IG's clock then */
    double last_t;            /* the time drawn last */
    uint32_t last_frame;      /* and its host frame */
} ig_clock;

static double clouds_time(ig_clock *c, const ig_args *a, const cu_sim_link *l, double t0, uint64_t elapsed_ns)
{
    double t;
    if (a->link.proto == CU_SIM_CIGI && l->cigi.timestamp_valid) {
        if (!c->have_ts) {
            c->ts_first = l->cigi.timestamp;
            c->have_ts = 1;
        }
        t = t0 + (double)(uint32_t)(l->cigi.timestamp - c->ts_first) * 1e-5;
        c->host_t = t;
        c->host_ns = elapsed_ns;
    } else if (c->have_ts && a->link.proto == CU_SIM_CIGI) {
        t = l->cigi.host_frame == c->last_frame ? c->last_t
            : c->host_t + (double)(elapsed_ns - c->host_ns) * 1e-9;
    } else {
        t = t0 + (double)elapsed_ns * 1e-9;
    }
    c->last_t = t;
    c->last_frame = a->link.proto == CU_SIM_CIGI ? l->cigi.host_frame : 0;
    return t;
}

static int run(cli_session *s, ig_args *a, cu_sim_link *l, ig_world *w)
{
    cu_sim_state st;
    memset(&st, 0, sizeof st);
    double t0 = cu_renderer_get_time(s->r), lat_hist[LATENCY_KEEP];
    uint64_t start = now_ns(), last_log = 0;
    ig_clock clk = {0};
    long frames = 0, nlat = 0;
    char err[512], notice[256] = "";
    int rc = 0;
    while (!quit_signal && (!a->frames_max || frames < a->frames_max)) {
        if (cu_sim_link_start_frame(l, (uint32_t)frames, (uint32_t)((now_ns() - start) / 10000)) < 0)
            fprintf(stderr, "cumulo ig: %s\n", l->last_error);
        wait_for_frame(l, &st, a->frame_timeout);
        /* What the host got wrong, logged at most once a second (every time with -v): a flood of bad datagrams
         * must not become a flood of log lines. */
        if (l->last_error[0]) {
            uint64_t t = now_ns();
            if (a->o.verbose || t - last_log >= 1000000000u) {
                fprintf(stderr, "cumulo ig: %s (%lu of %lu datagrams rejected so far)\n", l->last_error, l->rejected,
                        l->datagrams);
                last_log = t;
            }
            l->last_error[0] = 0;
        }
        double t = clouds_time(&clk, a, l, t0, now_ns() - start);
        cu_error e;
        if (cu_renderer_set_time(s->r, fmin(t, 1e9), &e) ||
            ig_world_apply(w, &st, s->r, s->width, s->height, (double)now_ns() * 1e-9, err, sizeof err)) {
            fprintf(stderr, "cumulo ig: %s\n", cu_renderer_get_time(s->r) == t ? err : e.msg);
            rc = 1;
            break;
        }
        if (w->notice[0] && strcmp(w->notice, notice)) {
            fprintf(stderr, "cumulo ig: %s\n", w->notice);
            snprintf(notice, sizeof notice, "%s", w->notice);
        }
        if (cli_session_render_view(s, w->have_camera ? w->view : NULL, w->have_camera ? w->proj : NULL)) {
            rc = 1;
            break;
        }
        double lat_ms = NAN;
        if (l->frame_ready) { /* from the datagram that opened the frame to the frame presented */
            lat_ms = (double)(now_ns() - l->frame_rx_ns) * 1e-6;
            lat_hist[nlat++ % LATENCY_KEEP] = lat_ms;
        }
        if (a->save_dir && save_frame(s, a->save_dir, frames)) {
            rc = 1;
            break;
        }
        if (a->trace)
            trace_line(a, l, w, s->r, frames, lat_ms);
        frames++;
    }
    double med, p95, mx, secs = (double)(now_ns() - start) * 1e-9;
    latency_stats(lat_hist, nlat, &med, &p95, &mx);
    const cu_cigi_stats *cs = &l->cigi.stats;
    printf("[ig] %s: frames=%ld FPS: %.1f datagrams=%lu rejected=%lu oversized=%lu layer_rebuilds=%lu\n",
           a->o.scene_path, frames, secs > 0 ? frames / secs : 0.0, l->datagrams, l->rejected, l->oversized,
           w->rebuilds);
    if (a->link.proto == CU_SIM_CIGI)
        printf("[ig] cigi: packets=%lu applied=%lu skipped=%lu unknown=%lu malformed=%lu wrong_version=%lu "
               "untrusted=%lu nonfinite=%lu out_of_range=%lu\n", cs->packets, cs->applied, cs->skipped,
               cs->skipped_unknown, cs->malformed, cs->wrong_version, cs->untrusted, cs->nonfinite, cs->out_of_range);
    printf("[ig] latency packet to presented frame: median=%.3f ms p95=%.3f ms max=%.3f ms over %ld frames\n", med,
           p95, mx, nlat < LATENCY_KEEP ? nlat : LATENCY_KEEP);
    fflush(stdout);
    return rc;
}

/* The scene drawn last: the file's text and the host's layers (ig_world.c). Every write is checked. */
static int dump_scene(const ig_world *w, const char *path)
{
    char layers[4096];
    size_t n = ig_layers_text(w->layers, w->geo.alt0, w->extent, layers, sizeof layers);
    FILE *f = fopen(path, "w");
    int bad = !f || fwrite(w->base_text, 1, w->base_len, f) != w->base_len || fwrite(layers, 1, n, f) != n;
    if (f && fclose(f))
        bad = 1;
    if (bad)
        fprintf(stderr, "cumulo ig: cannot write %s\n", path);
    return bad;
}

int cmd_ig(int argc, char **argv)
{
    ig_args a;
    int rc = parse_args(&a, argc, argv);
    if (rc >= 0)
        return rc;
    struct sigaction sa = { .sa_handler = on_signal };
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);

    if (!a.link.year) { /* X-Plane's date has no year: the one the wall clock shows */
        time_t now = time(NULL);
        struct tm tm;
        a.link.year = gmtime_r(&now, &tm) ? tm.tm_year + 1900 : 2026;
    }
    cli_session s = {0};
    rc = cli_session_open(&s, &a.o);
    if (rc) {
        cli_session_close(&s); /* what it opened before it failed (the scene) */
        return rc;
    }
    char err[512];
    ig_world w;
    static cu_sim_link link; /* 64 KiB of datagram buffer: not on the stack */
    if (ig_world_init(&w, s.scene, a.o.scene_path, a.extent, err, sizeof err) ||
        cu_sim_link_open(&link, &a.link, err, sizeof err)) {
        fprintf(stderr, "cumulo ig: %s\n", err);
        cli_session_close(&s);
        return 1;
    }
    char what[200];
    cu_sim_link_describe(&link, what, sizeof what);
    fprintf(stderr, "cumulo ig: %s, %dx%d, %s\n", what, s.width, s.height, cu_renderer_gl_string(s.r, 1));
    rc = run(&s, &a, &link, &w);
    if (a.dump_scene && dump_scene(&w, a.dump_scene))
        rc = 1;
    cu_sim_link_close(&link);
    ig_world_free(&w);
    cli_session_close(&s);
    return rc;
}
