/* app/cmd_run.c: `cumulo run` — the interactive/kiosk loop: a display back end (drm, x11, wayland, headless),
 * inputs that move the sun (GPIO knob, evdev keyboards and dials, stdin commands), and the renderer. */
#include "config.h"
#include "commands.h"
#include "session.h"
#include "evdev.h"
#include "input.h"
#include "stdin_input.h"
#include "sun_control.h"
#if CU_HAVE_GPIOD
#include "gpio.h"
#endif
#if CU_HAVE_DRM
#include "drm_mode.h"
#endif
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define MAX_INPUTS 8
#define MAX_ACTIONS 64

static volatile sig_atomic_t quit_signal;

static void on_signal(int sig)
{
    quit_signal = sig;
}

typedef struct run_input {
    cu_input_spec spec;
    int required;           /* asked for with --input (stdin read by default is not) */
    int open;
    int eof;                /* stdin ended normally (a script finished): not a failure */
    cu_evdev *ev;
#if CU_HAVE_GPIOD
    cu_gpio *gpio;
#endif
    cu_stdin in;
} run_input;

typedef struct run_state {
    cu_action acts[MAX_ACTIONS];
    int nacts;
    const char *source[MAX_ACTIONS];
    const char *cur_source;
} run_state;

static void usage(FILE *f)
{
    fprintf(f,
        "usage: cumulo run SCENE [--platform drm|x11|wayland|headless] [--frames N] [--size WxH] [--fullscreen]\n"
        "                  [--mode WxH[@Hz]] [--device /dev/dri/cardN] [--input SPEC]... [--no-stdin]\n"
        "                  [--knob azimuth|elevation] [--step DEG] [--accel K] [--sun-elevation-range MIN:MAX]\n"
        "                  [--sun-azimuth-range MIN:MAX] [--set section.key=value]... [-v]\n"
        "  --input gpio:chip=gpiochip0,a=17,b=27[,button=22][,steps=4][,debounce=1000]   rotary encoder (libgpiod)\n"
        "  --input evdev:/dev/input/event3 | evdev:name=NAME   keyboard (arrows, +/-) or dial (USB knob, encoder)\n"
        "  --input stdin       commands: sun EL AZ | elevation EL | azimuth AZ | turn N | toggle | status | quit\n"
        "  stdin is read by default unless --no-stdin. Each sun change is logged on stderr as\n"
        "  'sun elevation=E azimuth=A source=S'.\n");
    fprintf(f, "display back ends in this build:");
    for (int i = 0; cu_display_backends[i]; i++)
        fprintf(f, " %s", cu_display_backends[i]->name);
    fprintf(f, " (headless = egl)\n");
#if CU_HAVE_GPIOD
    fprintf(f, "gpio: %s\n", cu_gpio_api());
#else
    fprintf(f, "gpio: not built (no libgpiod)\n");
#endif
}

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void log_cb(void *user, cu_log_level level, const char *msg)
{
    static const char *names[] = {"error", "warning", "info", "debug"};
    if (level <= CU_LOG_WARN || *(const int *)user)
        fprintf(stderr, "cumulo: %s: %s\n", names[level], msg);
}

typedef struct proc_ctx { const cu_display_backend *be; cu_display *disp; } proc_ctx;
static void *getproc(void *user, const char *name)
{
    proc_ctx *p = user;
    return p->be->get_proc_address(p->disp, name);
}

static void push(run_state *st, const cu_action *a)
{
    if (st->nacts < MAX_ACTIONS) {
        st->source[st->nacts] = st->cur_source;
        st->acts[st->nacts++] = *a;
    }
}

static void on_line(void *user, const char *line)
{
    run_state *st = user;
    cu_action a;
    char err[256];
    if (!strcmp(line, CU_STDIN_OVERLONG)) {
        fprintf(stderr, "stdin: line longer than %d characters ignored\n", CU_STDIN_LINE_MAX - 1);
        return;
    }
    if (cu_stdin_parse(line, &a, err, sizeof err))
        fprintf(stderr, "%s\n", err);
    else if (a.kind != CU_ACT_NONE)
        push(st, &a);
}

static int open_input(run_input *in, int grab)
{
    char err[512];
    char desc[300];
    cu_input_describe(&in->spec, desc, sizeof desc);
    switch (in->spec.kind) {
    case CU_INPUT_STDIN:
        cu_stdin_init(&in->in, STDIN_FILENO);
        in->open = 1;
        return 0;
    case CU_INPUT_EVDEV:
        if (cu_evdev_open(&in->ev, &in->spec, grab, err, sizeof err)) {
            fprintf(stderr, "%s; continuing without it\n", err);
            return 1;
        }
        fprintf(stderr, "input: %s ('%s')\n", desc, cu_evdev_name(in->ev));
        in->open = 1;
        return 0;
    case CU_INPUT_GPIO:
#if CU_HAVE_GPIOD
        if (cu_gpio_open(&in->gpio, &in->spec, err, sizeof err)) {
            fprintf(stderr, "%s; continuing without it\n", err);
            return 1;
        }
        if (cu_gpio_note(in->gpio)[0])
            fprintf(stderr, "%s\n", cu_gpio_note(in->gpio));
        fprintf(stderr, "input: %s (%s)\n", desc, cu_gpio_api());
        in->open = 1;
        return 0;
#else
        fprintf(stderr, "gpio: this cumulo was built without libgpiod (install libgpiod-dev and rebuild); "
                "continuing without %s\n", desc);
        return 1;
#endif
    }
    return 1;
}

static void close_input(run_input *in)
{
    if (!in->open)
        return;
    if (in->ev)
        cu_evdev_close(in->ev);
#if CU_HAVE_GPIOD
    if (in->gpio)
        cu_gpio_close(in->gpio);
    in->gpio = NULL;
#endif
    in->ev = NULL;
    in->open = 0;
}

/* Polls every open input (timeout_ms: 0 = just look) and collects their actions into st. */
static void poll_inputs(run_input *ins, int nin, int timeout_ms, run_state *st)
{
    struct pollfd pfd[MAX_INPUTS * 3];
    int owner[MAX_INPUTS * 3];
    int n = 0;
    for (int i = 0; i < nin; i++) {
        if (!ins[i].open)
            continue;
        int fds[3], k = 0;
        if (ins[i].spec.kind == CU_INPUT_STDIN) {
            fds[k++] = STDIN_FILENO;
        } else if (ins[i].ev) {
            fds[k++] = cu_evdev_fd(ins[i].ev);
        }
#if CU_HAVE_GPIOD
        else if (ins[i].gpio) {
            k = cu_gpio_fds(ins[i].gpio, fds, 3);
        }
#endif
        for (int j = 0; j < k; j++) {
            pfd[n].fd = fds[j];
            pfd[n].events = POLLIN;
            pfd[n].revents = 0;
            owner[n++] = i;
        }
    }
    if (n == 0) {
        if (timeout_ms > 0) {
            struct timespec ts = { 0, (long)timeout_ms * 1000000L };
            nanosleep(&ts, NULL);
        }
        return;
    }
    if (poll(pfd, (nfds_t)n, timeout_ms) <= 0)
        return;
    int done[MAX_INPUTS] = {0};
    for (int p = 0; p < n; p++) {
        int i = owner[p];
        if (!pfd[p].revents || done[i] || !ins[i].open)
            continue;
        done[i] = 1;
        run_input *in = &ins[i];
        char err[512];
        cu_action acts[MAX_ACTIONS];
        int na = 0, gone = 0;
        if (in->spec.kind == CU_INPUT_STDIN) {
            st->cur_source = "stdin";
            if (cu_stdin_read(&in->in, on_line, st)) {
                close_input(in); /* end of input: a script ended, or the service has no terminal */
                in->eof = 1;
            }
            continue;
        }
        if (in->ev) {
            st->cur_source = "evdev";
            gone = cu_evdev_read(in->ev, acts, MAX_ACTIONS, &na, err, sizeof err);
        }
#if CU_HAVE_GPIOD
        else if (in->gpio) {
            st->cur_source = "gpio";
            gone = cu_gpio_read(in->gpio, acts, MAX_ACTIONS, &na, err, sizeof err);
        }
#endif
        for (int k = 0; k < na; k++)
            push(st, &acts[k]);
        if (gone) {
            fprintf(stderr, "%s\n", err);
            close_input(in);
        }
    }
}

static int parse_int(const char *opt, const char *v, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long x = strtol(v, &end, 10);
    if (end == v || *end || errno || x < lo || x > hi) {
        fprintf(stderr, "cumulo: %s expects a whole number in %ld..%ld, got '%s'\n", opt, lo, hi, v);
        return 1;
    }
    *out = x;
    return 0;
}

static int parse_double(const char *opt, const char *v, double lo, double hi, double *out)
{
    char *end;
    double x = strtod(v, &end);
    if (end == v || *end || !(x >= lo && x <= hi)) {
        fprintf(stderr, "cumulo: %s expects a number in %g..%g, got '%s'\n", opt, lo, hi, v);
        return 1;
    }
    *out = x;
    return 0;
}

int cmd_run(int argc, char **argv)
{
    cli_opts o = {0};
    cu_display_opts dopt = {0};
    run_input ins[MAX_INPUTS];
    int nin = 0, no_stdin = 0, knob_el = 0, have_step = 0, have_accel = 0;
    long frames_max = 0;
    double step = 1.0, accel = 0.25;
    const char *el_range = NULL, *az_range = NULL;
    memset(ins, 0, sizeof ins);

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int c = cli_common_option(&o, argc, argv, &i);
        if (c < 0)
            return 2;
        if (c > 0)
            continue;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 0;
        }
        if (!strcmp(a, "--fullscreen")) {
            dopt.fullscreen = 1;
            continue;
        }
        if (!strcmp(a, "--no-stdin")) {
            no_stdin = 1;
            continue;
        }
        if (a[0] == '-' && a[1]) {
            static const char *with_value[] = { "--frames", "--mode", "--device", "--input", "--knob", "--step",
                                                "--accel", "--sun-elevation-range", "--sun-azimuth-range" };
            int known = 0;
            for (size_t k = 0; k < sizeof with_value / sizeof with_value[0]; k++)
                known |= !strcmp(a, with_value[k]);
            if (!known) {
                fprintf(stderr, "cumulo run: unknown option '%s'\n", a);
                usage(stderr);
                return 2;
            }
            if (i + 1 >= argc) {
                fprintf(stderr, "cumulo: %s needs a value\n", a);
                return 2;
            }
            const char *v = argv[++i];
            if (!strcmp(a, "--frames")) {
                if (parse_int(a, v, 1, 2000000000L, &frames_max))
                    return 2;
            } else if (!strcmp(a, "--mode")) {
                dopt.mode = v;
            } else if (!strcmp(a, "--device")) {
                dopt.device = v;
            } else if (!strcmp(a, "--input")) {
                char err[512];
                if (nin == MAX_INPUTS) {
                    fprintf(stderr, "cumulo: at most %d --input options\n", MAX_INPUTS);
                    return 2;
                }
                if (cu_input_parse(v, &ins[nin].spec, err, sizeof err)) {
                    fprintf(stderr, "cumulo: %s\n", err);
                    return 2;
                }
                ins[nin++].required = 1;
            } else if (!strcmp(a, "--knob")) {
                if (strcmp(v, "azimuth") && strcmp(v, "elevation")) {
                    fprintf(stderr, "cumulo: --knob expects azimuth or elevation, got '%s'\n", v);
                    return 2;
                }
                knob_el = v[0] == 'e';
            } else if (!strcmp(a, "--step")) {
                if (parse_double(a, v, 0.001, 90.0, &step))
                    return 2;
                have_step = 1;
            } else if (!strcmp(a, "--accel")) {
                if (parse_double(a, v, 0.0, 100.0, &accel))
                    return 2;
                have_accel = 1;
            } else if (!strcmp(a, "--sun-elevation-range")) {
                el_range = v;
            } else {
                az_range = v;
            }
            continue;
        }
        if (o.scene_path) {
            fprintf(stderr, "cumulo run: one scene only ('%s' and '%s')\n", o.scene_path, a);
            return 2;
        }
        o.scene_path = a;
    }
    if (!o.scene_path) {
        usage(stderr);
        return 2;
    }

    /* Sun control settings are checked before anything opens, so a typo costs no mode switch. */
    cu_sun_ctl sun;
    cu_sun_ctl_init(&sun, 0, 0);
    char err[512];
    if ((el_range && cu_sun_parse_range("--sun-elevation-range", el_range, -90, 90, &sun.lim.el_min,
                                        &sun.lim.el_max, err, sizeof err)) ||
        (az_range && cu_sun_parse_range("--sun-azimuth-range", az_range, -720, 720, &sun.lim.az_min,
                                        &sun.lim.az_max, err, sizeof err))) {
        fprintf(stderr, "cumulo: %s\n", err);
        return 2;
    }
#if CU_HAVE_DRM
    if (dopt.mode) {
        int mw, mh;
        double mhz;
        if (cu_drm_parse_mode(dopt.mode, &mw, &mh, &mhz, err, sizeof err)) {
            fprintf(stderr, "cumulo: %s\n", err);
            return 2;
        }
    }
#endif
    int stdin_explicit = 0;
    for (int i = 0; i < nin; i++)
        stdin_explicit |= ins[i].spec.kind == CU_INPUT_STDIN;
    if (!no_stdin && !stdin_explicit && nin < MAX_INPUTS)
        ins[nin++].spec.kind = CU_INPUT_STDIN;

    const cu_display_backend *be = cu_display_find(o.backend);
    if (!be) {
        fprintf(stderr, "cumulo: no display back end '%s' in this build; built:", o.backend);
        for (int i = 0; cu_display_backends[i]; i++)
            fprintf(stderr, " %s", cu_display_backends[i]->name);
        fprintf(stderr, " (headless = egl)\n");
        return 2;
    }
    int headless = !strcmp(be->name, "egl") || !strcmp(be->name, "osmesa");

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal; /* no SA_RESTART: a blocked poll returns and the loop sees the flag */
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);

    int rc = 1;
    cu_error e;
    cu_scene *scene = NULL;
    cu_renderer *r = NULL;
    cu_display *disp = NULL;
    if (cu_scene_load(&scene, o.scene_path, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return 1;
    }
    for (int i = 0; i < o.nsets; i++)
        if (cu_scene_set(scene, o.sets[i], &e)) {
            fprintf(stderr, "%s\n", e.msg);
            goto out;
        }
    cu_scene_output_size(scene, &dopt.width, &dopt.height);
    if (o.width) {
        dopt.width = o.width;
        dopt.height = o.height;
    }
    if (be->open(&disp, &dopt, err, sizeof err)) {
        fprintf(stderr, "cumulo: %s\n", err);
        disp = NULL;
        goto out;
    }
    proc_ctx pc = { be, disp };
    int verbose = o.verbose;
    cu_desc desc = {0};
    desc.get_proc_address = getproc;
    desc.get_proc_user = &pc;
    desc.log = log_cb;
    desc.log_user = &verbose;
    if (cu_renderer_create(&r, &desc, &e) || cu_renderer_set_scene(r, scene, &e)) {
        fprintf(stderr, "cumulo: %s\n", e.msg);
        goto out;
    }

    /* Inputs after the display: on a kiosk the screen matters more, and evdev grabbing needs to know the platform. */
    int required = 0, opened_required = 0;
    for (int i = 0; i < nin; i++) {
        required += ins[i].required;
        if (open_input(&ins[i], !strcmp(be->name, "drm")) == 0)
            opened_required += ins[i].required;
    }
    if (required && !opened_required) {
        fprintf(stderr, "cumulo: none of the %d requested inputs could be opened (see above)\n", required);
        goto out;
    }

    double el0, az0;
    cu_renderer_get_sun(r, &el0, &az0);
    cu_sun_ctl_init(&sun, el0, az0);
    if (el_range)
        cu_sun_parse_range("--sun-elevation-range", el_range, -90, 90, &sun.lim.el_min, &sun.lim.el_max, err,
                           sizeof err);
    if (az_range)
        cu_sun_parse_range("--sun-azimuth-range", az_range, -720, 720, &sun.lim.az_min, &sun.lim.az_max, err,
                           sizeof err);
    cu_sun_ctl_clamp(&sun.lim, &sun.el, &sun.az);
    sun.axis = knob_el ? CU_SUN_ELEVATION : CU_SUN_AZIMUTH;
    if (have_step) {
        sun.step_az = step;
        sun.step_el = step / 2.0;
    }
    if (have_accel)
        sun.accel = accel;
    if (sun.el != el0 || sun.az != az0) {
        if (cu_renderer_set_sun(r, sun.el, sun.az, &e))
            fprintf(stderr, "cumulo: %s\n", e.msg);
    }

    unsigned fbo;
    int w, h;
    be->frame(disp, &fbo, &w, &h);
    char surface[512];
    be->describe(disp, surface, sizeof surface);
    char inputs[1024] = "";
    for (int i = 0; i < nin; i++) {
        if (!ins[i].open)
            continue;
        char d[300];
        cu_input_describe(&ins[i].spec, d, sizeof d);
        size_t used = strlen(inputs);
        snprintf(inputs + used, sizeof inputs - used, "%s%s", used ? ", " : "", d);
    }
    printf("=======================================================\n"
           "    cumulo run %s\n"
           "=======================================================\n"
           "    GL_VENDOR:     %s\n"
           "    GL_RENDERER:   %s\n"
           "    GL_VERSION:    %s\n"
           "    Surface:       %s\n"
           "    Size:          %dx%d\n"
           "    Inputs:        %s\n"
           "    Sun:           elevation=%.3f azimuth=%.3f knob=%s\n"
           "=======================================================\n",
           o.scene_path, cu_renderer_gl_string(r, 0), cu_renderer_gl_string(r, 1), cu_renderer_gl_string(r, 2),
           surface, w, h, inputs[0] ? inputs : "(none)", sun.el, sun.az,
           sun.axis == CU_SUN_AZIMUTH ? "azimuth" : "elevation");
    fflush(stdout);

    uint64_t t_start = now_ns();
    long frames = 0;
    int quit = 0;
    rc = 0;
    while (!quit && !quit_signal && (!frames_max || frames < frames_max)) {
        run_state st;
        st.nacts = 0;
        st.cur_source = "stdin";
        /* Headless without a frame count has no vsync to pace it: wait for input up to a 60 Hz frame instead of
         * spinning. */
        poll_inputs(ins, nin, headless && !frames_max ? 16 : 0, &st);
        int moved = 0;
        for (int k = 0; k < st.nacts; k++) {
            const cu_action *a = &st.acts[k];
            if (a->kind == CU_ACT_QUIT) {
                quit = 1;
                break;
            }
            if (a->kind == CU_ACT_STATUS) {
                printf("status elevation=%.3f azimuth=%.3f knob=%s frames=%ld\n", sun.el, sun.az,
                       sun.axis == CU_SUN_AZIMUTH ? "azimuth" : "elevation", frames);
                fflush(stdout);
            }
            if (a->kind == CU_ACT_TOGGLE)
                fprintf(stderr, "knob axis=%s source=%s\n", sun.axis == CU_SUN_AZIMUTH ? "elevation" : "azimuth",
                        st.source[k]);
            if (cu_sun_ctl_apply(&sun, a)) {
                moved = 1;
                fprintf(stderr, "sun elevation=%.3f azimuth=%.3f source=%s\n", sun.el, sun.az, st.source[k]);
            }
        }
        /* One sun pass per frame however many detents or commands arrived since the last one. */
        if (moved && cu_renderer_set_sun(r, sun.el, sun.az, &e))
            fprintf(stderr, "cumulo: %s\n", e.msg);
        if (quit)
            break;
        int still_required = 0, any_open = 0, any_eof = 0;
        for (int i = 0; i < nin; i++) {
            still_required += ins[i].required && (ins[i].open || ins[i].eof);
            any_open |= ins[i].open;
            any_eof |= ins[i].eof;
        }
        if (required && !still_required) {
            fprintf(stderr, "cumulo: no requested input is left (see above); exiting\n");
            rc = 1;
            break;
        }
        if (headless && !frames_max && !any_open && any_eof)
            break; /* headless, no frame count, and the command stream ended: nothing can change any more */
        be->frame(disp, &fbo, &w, &h);
        cu_frame f = { fbo, w, h, 0 };
        if (cu_render(r, &f, &e)) {
            fprintf(stderr, "cumulo: %s\n", e.msg);
            rc = 1;
            break;
        }
        int pr = be->present(disp, err, sizeof err);
        if (pr < 0)
            break; /* the window was closed */
        if (pr > 0) {
            fprintf(stderr, "cumulo: %s\n", err);
            rc = 1;
            break;
        }
        frames++;
    }
    double secs = (double)(now_ns() - t_start) * 1e-9;
    if (quit_signal)
        fprintf(stderr, "cumulo: %s, stopping\n", quit_signal == SIGINT ? "interrupted" : "terminated");
    printf("[run] %s: frames=%ld FPS: %.1f FrameTime: %.3f ms\n", o.scene_path, frames,
           secs > 0 ? frames / secs : 0.0, frames ? secs * 1000.0 / frames : 0.0);
    fflush(stdout);

out:
    for (int i = 0; i < nin; i++)
        close_input(&ins[i]);
    if (r)
        cu_renderer_destroy(r);
    if (disp)
        be->close(disp); /* DRM: puts the previous CRTC (the console) back */
    if (scene)
        cu_scene_free(scene);
    return rc;
}
