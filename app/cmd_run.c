/* app/cmd_run.c: `cumulo run` — the interactive/kiosk loop: a display back end (drm, x11, wayland, headless),
 * inputs that move the sun (GPIO knob, evdev keyboards and dials, stdin commands) or, with --clock, the time of day
 * the sun follows, and the renderer. */
#include "config.h"
#include "commands.h"
#include "session.h"
#include "drm_mode.h"
#include "input_set.h"
#include "run_clock.h"
#include "run_usage.h"
#include "sun_control.h"
#include <errno.h>
#include <getopt.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_ACTIONS 64

static volatile sig_atomic_t quit_signal;

static void on_signal(int sig) { quit_signal = sig; }

/* What the command line asked for; all of it is checked before anything opens, so a typo costs no mode switch. */
typedef struct run_args {
    cli_opts o;
    cu_display_opts dopt;
    cu_input_set inputs;
    int no_stdin;
    long frames_max;
    long wait_display;              /* seconds to retry opening the display (--wait-display) */
    const char *el_range, *az_range;
    const char *step;               /* --step: degrees, or minutes with --clock (read once all options are in) */
    cu_sun_ctl sun;                 /* the knob settings; the sun itself comes from the scene */
    int clock;                      /* --clock: the sun follows the wall clock, the knob offsets the time */
    const char *clock_only;         /* the first of --clock-offset and --time-scale given: they need --clock */
    cu_clock_ctl clk;               /* --clock-offset, --time-scale, the knob's minutes */
} run_args;

/* The display, its renderer and the scene, opened as every subcommand opens them (app/session.c). */
typedef cli_session run_session;

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void input_log(void *user, const char *msg) { (void)user; fprintf(stderr, "%s\n", msg); }

/* A number in lo..hi; 0, or 1 after printing what the option expects. */
static int parse_number(const char *opt, const char *v, double lo, double hi, double *out)
{
    char *end;
    double x = strtod(v, &end);
    if (end == v || *end || !(x >= lo && x <= hi)) {
        fprintf(stderr, "cumulo run: %s expects a number in %g..%g, got '%s'\n", opt, lo, hi, v);
        return 1;
    }
    *out = x;
    return 0;
}

/* Above app/session.h's CLI_OPT_* ids, which the common options keep. */
enum { OPT_FULLSCREEN = 0x200, OPT_NO_STDIN, OPT_FRAMES, OPT_MODE, OPT_DEVICE, OPT_INPUT, OPT_KNOB,
       OPT_STEP, OPT_ACCEL, OPT_EL_RANGE, OPT_AZ_RANGE, OPT_VERSION, OPT_WAIT_DISPLAY, OPT_CLOCK, OPT_CLOCK_OFFSET,
       OPT_TIME_SCALE };

#define ARG(name, id) { name, required_argument, NULL, id }
#define FLAG(name, id) { name, no_argument, NULL, id }
static const struct option long_opts[] = {
    FLAG("help", 'h'), FLAG("verbose", 'v'), FLAG("fullscreen", OPT_FULLSCREEN), FLAG("no-stdin", OPT_NO_STDIN),
    ARG("size", CLI_OPT_SIZE), ARG("backend", CLI_OPT_BACKEND), ARG("platform", CLI_OPT_BACKEND), ARG("set", CLI_OPT_SET),
    ARG("frames", OPT_FRAMES), ARG("mode", OPT_MODE), ARG("device", OPT_DEVICE), ARG("input", OPT_INPUT),
    ARG("knob", OPT_KNOB), ARG("step", OPT_STEP), ARG("accel", OPT_ACCEL), ARG("sun-elevation-range", OPT_EL_RANGE),
    ARG("sun-azimuth-range", OPT_AZ_RANGE), ARG("wait-display", OPT_WAIT_DISPLAY), ARG("data-dir", CLI_OPT_DATA_DIR), FLAG("version", OPT_VERSION),
    FLAG("clock", OPT_CLOCK), ARG("clock-offset", OPT_CLOCK_OFFSET), ARG("time-scale", OPT_TIME_SCALE),
    { NULL, 0, NULL, 0 },
};

/* One option and its value; 0, or 1 after printing why the value is wrong. */
static int take_option(run_args *a, int c, const char *name, char *v)
{
    char err[512] = "";
    switch (c) {
    case 'v': a->o.verbose = 1; return 0;
    case OPT_FULLSCREEN: a->dopt.fullscreen = 1; return 0;
    case OPT_NO_STDIN: a->no_stdin = 1; return 0;
    case OPT_MODE: a->dopt.mode = v; return 0;
    case OPT_DEVICE: a->dopt.device = v; return 0;
    case OPT_ACCEL:
        if (parse_number(name, v, 0.0, 100.0, &a->sun.speed.accel))
            return 1;
        a->clk.speed.accel = a->sun.speed.accel;
        return 0;
    case OPT_CLOCK: a->clock = 1; return 0;
    case OPT_CLOCK_OFFSET:
    case OPT_TIME_SCALE:
        a->clock_only = a->clock_only ? a->clock_only : c == OPT_CLOCK_OFFSET ? "--clock-offset" : "--time-scale";
        return run_clock_option(&a->clk, name, v);
    case OPT_FRAMES:
        if (cli_parse_counts(v, 0, 1, 1, 2000000000L, &a->frames_max)) {
            fprintf(stderr, "cumulo: %s expects a whole number in 1..2000000000, got '%s'\n", name, v);
            return 1;
        }
        return 0;
    case OPT_WAIT_DISPLAY:
        if (cli_parse_counts(v, 0, 1, 0, 3600, &a->wait_display)) {
            fprintf(stderr, "cumulo: %s expects whole seconds in 0..3600, got '%s'\n", name, v);
            return 1;
        }
        return 0;
    case OPT_STEP: a->step = v; return 0;
    case CLI_OPT_SIZE: case CLI_OPT_BACKEND: case CLI_OPT_SET: case CLI_OPT_DATA_DIR:
        return cli_common_getopt(&a->o, c, v, "cumulo") < 0;
    case OPT_EL_RANGE: a->el_range = v; return 0;
    case OPT_AZ_RANGE: a->az_range = v; return 0;
    case OPT_INPUT:
        if (!cu_input_set_add(&a->inputs, v, err, sizeof err))
            return 0;
        break;
    case OPT_KNOB:
        if (strcmp(v, "azimuth") && strcmp(v, "elevation")) {
            snprintf(err, sizeof err, "--knob expects azimuth or elevation, got '%s'", v);
            break;
        }
        a->sun.axis = v[0] == 'e' ? CU_SUN_ELEVATION : CU_SUN_AZIMUTH;
        return 0;
    }
    fprintf(stderr, "cumulo: %s\n", err);
    return 1;
}

/* Fills a from the command line and checks it. Returns -1 to go on, or the exit status: 0 after --help, 2 after a
 * usage error (one line printed). getopt_long returns the words in order ('-'), so errors come in the order given. */
static int parse_args(run_args *a, int argc, char **argv)
{
    memset(a, 0, sizeof *a);
    cu_sun_ctl_init(&a->sun, 0, 0);
    cu_clock_ctl_init(&a->clk);
    opterr = 0;
    optind = 1;
    for (;;) {
        int at = optind, idx = -1;
        int c = getopt_long(argc, argv, "-:hv", long_opts, &idx);
        if (c == -1 && at == argc)
            break;
        char name[40];
        snprintf(name, sizeof name, "--%s", idx >= 0 ? long_opts[idx].name : "");
        if (c == 'h') {
            run_usage(stdout);
            return 0;
        } else if (c == OPT_VERSION) {
            cli_print_version(stdout, "cumulo");
            return 0;
        } else if (c == '?' || c == -1) { /* -1 before the end: "--", never the end of the options here */
            fprintf(stderr, "cumulo run: unknown option '%s'\n", argv[at]);
            run_usage(stderr);
            return 2;
        } else if (c == ':') {
            fprintf(stderr, "cumulo: %s needs a value\n", argv[at]);
            return 2;
        } else if (c == 1) {
            if (a->o.scene_path) {
                fprintf(stderr, "cumulo run: one scene only ('%s' and '%s')\n", a->o.scene_path, optarg);
                return 2;
            }
            a->o.scene_path = optarg;
        } else if (take_option(a, c, name, optarg)) {
            return 2;
        }
    }
    if (!a->o.scene_path) {
        run_usage(stderr);
        return 2;
    }
    if (a->clock_only && !a->clock) {
        fprintf(stderr, "cumulo run: %s needs --clock\n", a->clock_only);
        return 2;
    }
    /* The values checked once all are in: a later --sun-*-range replaces an earlier one, as it always has; --step is
     * minutes or degrees as --clock, wherever it stands, says. */
    double step;
    if (a->step && a->clock) {
        if (parse_number("--step", a->step, 0.001, CU_OFFSET_MAX_MIN, &step))
            return 2;
        a->clk.step_s = step * 60.0;
    } else if (a->step) {
        if (parse_number("--step", a->step, 0.001, 90.0, &step))
            return 2;
        a->sun.step_az = step;
        a->sun.step_el = step / 2.0;
    }
    char err[512];
    cu_sun_limits *lim = &a->sun.lim;
    int mw, mh;
    double mhz;
    if ((a->el_range && cu_sun_parse_range("--sun-elevation-range", a->el_range, -90, 90, &lim->el_min,
                                           &lim->el_max, err, sizeof err)) ||
        (a->az_range && cu_sun_parse_range("--sun-azimuth-range", a->az_range, -720, 720, &lim->az_min,
                                           &lim->az_max, err, sizeof err)) ||
        (CU_HAVE_DRM && a->dopt.mode && cu_drm_parse_mode(a->dopt.mode, &mw, &mh, &mhz, err, sizeof err))) {
        fprintf(stderr, "cumulo: %s\n", err);
        return 2;
    }
    if (!a->no_stdin)
        cu_input_set_add_stdin(&a->inputs);
    return -1;
}

/* Display and renderer, retried for up to --wait-display seconds: at boot the KMS driver (vc4 on a Pi) can probe after
 * the kiosk starts, and waiting here for the one device it needs beats systemd-udev-settle waiting for all of them. */
static int attach_display(run_session *s, const run_args *a)
{
    char err[600];
    uint64_t end = now_ns() + (uint64_t)a->wait_display * 1000000000u;
    for (int tries = 0;; tries++) {
        if (!cli_session_attach(s, s->be, &a->dopt, cli_data_dir(&a->o), a->o.verbose, err, sizeof err))
            return 0;
        if (s->r)
            cu_renderer_destroy(s->r);
        if (s->disp)
            s->be->close(s->disp);
        s->r = NULL;
        s->disp = NULL;
        if (quit_signal || now_ns() >= end) {
            fprintf(stderr, "cumulo: %s\n", err);
            return 1;
        }
        if (!tries)
            fprintf(stderr, "cumulo: %s; retrying for up to %ld s\n", err, a->wait_display);
        struct timespec pause = { 0, 250000000 };
        nanosleep(&pause, NULL);
    }
}

/* Scene, display, renderer; 0, or the exit status after printing why not (2: a bad --set). */
static int open_session(run_session *s, run_args *a)
{
    cu_error e;
    if (cu_scene_load(&s->scene, a->o.scene_path, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return 1;
    }
    for (int i = 0; i < a->o.nsets; i++)
        if (cu_scene_set(s->scene, a->o.sets[i], &e)) {
            fprintf(stderr, "%s\n", e.msg);
            return 2;
        }
    cu_scene_output_size(s->scene, &a->dopt.width, &a->dopt.height);
    if (a->o.width) {
        a->dopt.width = a->o.width;
        a->dopt.height = a->o.height;
    }
    if (attach_display(s, a))
        return 1;
    if (cu_renderer_set_scene(s->r, s->scene, &e)) {
        fprintf(stderr, "cumulo: %s\n", e.msg);
        return 1;
    }
    return 0;
}

static const char *axis_name(cu_sun_axis axis) { return axis == CU_SUN_AZIMUTH ? "azimuth" : "elevation"; }

/* Applies what the inputs said, one sun pass however many detents or commands came. Returns 1 on quit. */
static int apply_actions(const cu_action *acts, const char **source, int n, cu_sun_ctl *sun, run_clock *clock,
                         cu_renderer *r, long frames, int *changed)
{
    int moved = 0, k;
    cu_error e;
    for (k = 0; k < n && acts[k].kind != CU_ACT_QUIT; k++) {
        const cu_action *a = &acts[k];
        if (clock) {
            run_clock_action(clock, a, source[k], r, frames);
            continue;
        }
        if (a->kind == CU_ACT_SET_OFFSET)
            fprintf(stderr, "%s: 'offset' needs --clock (without it the knob turns the sun's angles)\n", source[k]);
        if (a->kind == CU_ACT_STATUS) {
            printf("status elevation=%.3f azimuth=%.3f knob=%s frames=%ld\n", sun->el, sun->az,
                   axis_name(sun->axis), frames);
            fflush(stdout);
        }
        if (a->kind == CU_ACT_TOGGLE)
            fprintf(stderr, "knob axis=%s source=%s\n", axis_name(!sun->axis), source[k]);
        if (cu_sun_ctl_apply(sun, a)) {
            moved = 1;
            fprintf(stderr, "sun elevation=%.3f azimuth=%.3f source=%s\n", sun->el, sun->az, source[k]);
        }
    }
    if (moved && cu_renderer_set_sun(r, sun->el, sun->az, &e))
        fprintf(stderr, "cumulo: %s\n", e.msg);
    *changed |= moved;
    return k < n; /* stopped at a quit */
}

/* The knob as the command line set it up, from the scene's sun inside the limits. */
static void init_sun(cu_sun_ctl *sun, const run_args *a, cu_renderer *r)
{
    double el0, az0;
    cu_error e;
    cu_renderer_get_sun(r, &el0, &az0);
    cu_sun_ctl_start(sun, &a->sun, el0, az0);
    if ((sun->el != el0 || sun->az != az0) && cu_renderer_set_sun(r, sun->el, sun->az, &e))
        fprintf(stderr, "cumulo: %s\n", e.msg);
}

/* glmark2-style header: GL strings, surface, inputs, sun. */
static void print_header(const run_session *s, const run_args *a, const cu_sun_ctl *sun, const run_clock *clock)
{
    unsigned fbo;
    int w, h;
    char surface[512], inputs[1024];
    s->be->frame(s->disp, &fbo, &w, &h);
    s->be->describe(s->disp, surface, sizeof surface);
    cu_input_set_describe(&a->inputs, inputs, sizeof inputs);
    const char *bar = "=======================================================";
    printf("%s\n    cumulo run %s\n%s\n", bar, a->o.scene_path, bar);
    printf("    GL_VENDOR:     %s\n    GL_RENDERER:   %s\n    GL_VERSION:    %s\n", cu_renderer_gl_string(s->r, 0),
           cu_renderer_gl_string(s->r, 1), cu_renderer_gl_string(s->r, 2));
    printf("    Surface:       %s\n    Size:          %dx%d\n    Inputs:        %s\n", surface, w, h,
           inputs[0] ? inputs : "(none)");
    if (clock)
        run_clock_header(clock, s->r);
    else
        printf("    Sun:           elevation=%.3f azimuth=%.3f knob=%s\n", sun->el, sun->az, axis_name(sun->axis));
    printf("%s\n", bar);
    fflush(stdout);
}

/* A missing or vanished input is a warning, never the end: a kiosk unit (Restart=always) that exited here would
 * restart into the same missing device forever and show no sky at all. */
static void warn_inputs_gone(const cu_input_set *in, const char *what, int clock)
{
    int open, ended;
    cu_input_set_left(in, &open, &ended);
    fprintf(stderr, "cumulo: warning: %s (see above); the sky keeps running %s\n", what,
            open ? "with the inputs left"
                 : clock ? "with no input (the sun follows the clock)" : "with no input (the sun stays where it is)");
}

static int run_loop(run_session *s, run_args *a, cu_sun_ctl *sun, run_clock *clock)
{
    /* Headless without a frame count has no vsync: wait for input up to a 60 Hz frame instead of spinning. */
    int idle_headless = (!strcmp(s->be->name, "egl") || !strcmp(s->be->name, "osmesa")) && !a->frames_max;
    /* Nothing moved, nothing redrawn: without --clock (clouds drifting) or --frames (a measurement), on DRM/KMS (the
     * last flip stays on screen) and headless, a frame in which nothing changed is not drawn once the picture has
     * settled (cu_renderer_settled: a temporal grid needs G^2 frames): the loop waits for input (100 ms at most). Windows are redrawn every frame (an uncovered window needs its pixels). */
    int hold = !clock && !a->frames_max && (idle_headless || !strcmp(s->be->name, "drm"));
    int dirty = 1, last_w = -1, last_h = -1;
    long frames = 0, drawn = 0;
    uint64_t t_start = now_ns();
    int rc = 0, any_open, any_ended;
    int steered = cu_input_set_left(&a->inputs, &any_open, &any_ended) > 0; /* a requested input is there */
    while (!quit_signal && (!a->frames_max || frames < a->frames_max)) {
        cu_action acts[MAX_ACTIONS];
        const char *source[MAX_ACTIONS];
        int n = cu_input_set_poll(&a->inputs, hold && !dirty ? 100 : idle_headless ? 16 : 0, acts, source,
                                  MAX_ACTIONS);
        if (apply_actions(acts, source, n, sun, clock, s->r, frames, &dirty))
            break;
        if (!cu_input_set_left(&a->inputs, &any_open, &any_ended) && steered) {
            warn_inputs_gone(&a->inputs, "no requested input is left", clock != NULL);
            steered = 0;
        }
        if (idle_headless && !any_open && any_ended)
            break; /* the command stream ended and there is no frame count: nothing more can be asked or seen */
        if (clock)
            run_clock_tick(clock, s->r);
        unsigned fbo;
        int w, h, pr;
        char err[512];
        cu_error e;
        s->be->frame(s->disp, &fbo, &w, &h);
        if (hold && !dirty && w == last_w && h == last_h) {
            frames++; /* the picture on the screen is still this frame's */
            continue;
        }
        cu_frame f = {.fbo = fbo, .width = w, .height = h};
        if (cu_render(s->r, &f, &e)) {
            fprintf(stderr, "cumulo: %s\n", e.msg);
            rc = 1;
            break;
        }
        if ((pr = s->be->present(s->disp, err, sizeof err)) != 0) {
            if (pr > 0)
                fprintf(stderr, "cumulo: %s\n", err);
            rc = pr > 0;
            break; /* < 0: the window was closed */
        }
        frames++;
        drawn++;
        dirty = !cu_renderer_settled(s->r); /* a temporal grid marches the rest of the picture in the next frames */
        last_w = w, last_h = h;
    }
    double secs = (double)(now_ns() - t_start) * 1e-9;
    if (quit_signal)
        fprintf(stderr, "cumulo: %s, stopping\n", quit_signal == SIGINT ? "interrupted" : "terminated");
    printf("[run] %s: frames=%ld FPS: %.1f FrameTime: %.3f ms drawn=%ld\n", a->o.scene_path, frames,
           secs > 0 ? frames / secs : 0.0, frames ? secs * 1000.0 / frames : 0.0, drawn);
    fflush(stdout);
    return rc;
}

int cmd_run(int argc, char **argv)
{
    run_args a;
    int rc = parse_args(&a, argc, argv);
    if (rc >= 0)
        return rc;
    run_session s = { .be = cu_display_find(a.o.backend) };
    if (!s.be) {
        fprintf(stderr, "cumulo: no display back end '%s' in this build; built:", a.o.backend);
        run_list_display_backends(stderr);
        return 2;
    }

    struct sigaction sa = { .sa_handler = on_signal }; /* no SA_RESTART: a blocked poll returns, the loop sees it */
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);

    rc = open_session(&s, &a);
    if (rc == 0) {
        /* Inputs after the display: on a kiosk the screen matters more, and evdev grabs only on a bare console. */
        cu_input_opts io = { .grab = !strcmp(s.be->name, "drm"), .log = input_log };
        if (cu_input_set_open(&a.inputs, &io) == 0 && a.inputs.nrequired) {
            char what[96];
            snprintf(what, sizeof what, "none of the %d requested inputs could be opened", a.inputs.nrequired);
            warn_inputs_gone(&a.inputs, what, a.clock);
        }
        cu_sun_ctl sun;
        run_clock clock;
        if (a.clock)
            run_clock_start(&clock, &a.clk, s.scene, a.o.scene_path, s.r);
        else
            init_sun(&sun, &a, s.r);
        print_header(&s, &a, &sun, a.clock ? &clock : NULL);
        rc = run_loop(&s, &a, &sun, a.clock ? &clock : NULL);
    }
    cu_input_set_close(&a.inputs);
    cli_session_close(&s); /* DRM: puts the previous CRTC (the console) back */
    return rc;
}
