/* app/cmd_bench.c: `cumulo bench`: renders N frames after warm-up and prints glmark2-style lines with the
 * median and 95th percentile frame time (wall clock per frame including glFinish); optional CSV. */
#include "commands.h"
#include "session.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static const char bench_help[] =
    "usage: cumulo bench SCENE [options]\n"
    "Renders N frames after a warm-up and prints a glmark2-style line with the median and 95th-percentile frame\n"
    "time (wall clock per frame, including glFinish).\n"
    "  --frames N             frames measured (default 30)\n"
    "  --warmup N             frames rendered first and not measured (default 3)\n"
    "  --csv FILE             append one row to FILE (header written when the file is new)\n"
    "  --sun-every-frame      move the sun 0.01 deg of azimuth each frame (measures the sun-dependent passes)\n"
    "  --passes               time each pass too and print their medians (GPU timestamps where the context\n"
    "                         has them, else the wall clock with glFinish between passes)\n"
    "  --time-step S          advance the scene time S seconds each frame (wind, life cycles, boil, time_utc)\n"
    "  --sun-step DEG         the same with DEG per frame, in (0, 360]\n"
    "  --sun-blocks N         with the two above: the sun turned for N frames, then held for N, in turn, and the\n"
    "                         mean frame time of each kind and their ratio printed (what turning the sun costs,\n"
    "                         measured in one run; held frames count once the picture has settled)\n"
    "  --camera MODE          static (the scene's [camera], default); orbit: a new pose every frame, passed as\n"
    "                         view and projection matrices, circling the vertical through look_at; both: every\n"
    "                         orbit pose twice, just after the move and again unmoved, and the ratio of the two\n"
    "                         medians (what a moving camera costs, measured in one run)\n"
    "  --orbit-step DEG       degrees of orbit per frame (default 1), in (0, 360]\n" CLI_COMMON_HELP;

enum { CAM_STATIC, CAM_ORBIT, CAM_BOTH };

/* The scene's camera turned by deg about the vertical through its look_at, as host matrices. */
static int orbit_pose(cu_scene *sc, double deg, double aspect, float view[16], float proj[16])
{
    double p[3], l[3], fov;
    cu_scene_camera(sc, p, l, &fov);
    double a = deg * 3.14159265358979323846 / 180.0, dx = p[0] - l[0], dz = p[2] - l[2];
    char set[160];
    snprintf(set, sizeof set, "camera.position=%.17g %.17g %.17g", l[0] + dx * cos(a) - dz * sin(a), p[1],
             l[2] + dx * sin(a) + dz * cos(a));
    cu_error e;
    /* moved for the matrices only, then put back: every pose turns from the scene's own camera */
    if (cu_scene_set(sc, set, &e) ||
        cu_scene_camera_matrices(sc, aspect, 1.0, 1e5, view, proj, &e)) {
        fprintf(stderr, "cumulo bench: orbit: %s\n", e.msg);
        return 1;
    }
    snprintf(set, sizeof set, "camera.position=%.17g %.17g %.17g", p[0], p[1], p[2]);
    return cu_scene_set(sc, set, &e) != 0;
}

static double median(double *t, int n)
{
    qsort(t, (size_t)n, sizeof *t, cmp_double);
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

static int parse_count(const char *opt, const char *v, int min, int *out)
{
    long n;
    if (cli_parse_counts(v, 0, 1, min, 1000000, &n)) {
        fprintf(stderr, "cumulo bench: %s expects a count, got '%s'\n", opt, v);
        return -1;
    }
    *out = (int)n;
    return 0;
}

enum { OPT_FRAMES = 0x200, OPT_WARMUP, OPT_CSV, OPT_SUN_STEP, OPT_SUN_EVERY, OPT_CAMERA, OPT_ORBIT_STEP,
       OPT_TIME_STEP, OPT_PASSES, OPT_SUN_BLOCKS };

int cmd_bench(int argc, char **argv)
{
    static const struct option longopts[] = {
        CLI_COMMON_LONGOPTS,
        {"frames", required_argument, NULL, OPT_FRAMES},
        {"warmup", required_argument, NULL, OPT_WARMUP},
        {"csv", required_argument, NULL, OPT_CSV},
        {"sun-step", required_argument, NULL, OPT_SUN_STEP},
        {"sun-every-frame", no_argument, NULL, OPT_SUN_EVERY},
        {"camera", required_argument, NULL, OPT_CAMERA},
        {"orbit-step", required_argument, NULL, OPT_ORBIT_STEP},
        {"time-step", required_argument, NULL, OPT_TIME_STEP},
        {"passes", no_argument, NULL, OPT_PASSES},
        {"sun-blocks", required_argument, NULL, OPT_SUN_BLOCKS},
        {NULL, 0, NULL, 0},
    };
    cli_opts o = {0};
    int frames = 30, warmup = 3, sun_every_frame = 0, camera = CAM_STATIC, passes = 0, sun_blocks = 0;
    double orbit_step = 1.0;
    double sun_step = 0.01; /* degrees of azimuth per frame with --sun-every-frame: a knob turned slowly */
    double time_step = 0;   /* s of scene time per frame */
    const char *csv = NULL;
    int c;
    opterr = 0;
    optind = 1;
    while ((c = getopt_long(argc, argv, ":vh", longopts, NULL)) != -1) {
        int k = cli_common_getopt(&o, c, optarg, "cumulo bench");
        if (k < 0)
            return 2;
        if (k)
            continue;
        char *end;
        switch (c) {
        case OPT_FRAMES:
            if (parse_count("--frames", optarg, 1, &frames))
                return 2;
            break;
        case OPT_WARMUP:
            if (parse_count("--warmup", optarg, 0, &warmup))
                return 2;
            break;
        case OPT_CSV: csv = optarg; break;
        case OPT_SUN_STEP:
            sun_step = strtod(optarg, &end);
            if (end == optarg || *end || !(sun_step > 0) || sun_step > 360) {
                fprintf(stderr, "cumulo bench: --sun-step expects degrees in (0, 360], got '%s'\n", optarg);
                return 2;
            }
            sun_every_frame = 1;
            break;
        case OPT_SUN_EVERY: sun_every_frame = 1; break; /* measure the sun pass too, as when a knob turns */
        case OPT_PASSES: passes = 1; break;
        case OPT_SUN_BLOCKS:
            if (parse_count("--sun-blocks", optarg, 1, &sun_blocks))
                return 2;
            break;
        case OPT_TIME_STEP:
            time_step = strtod(optarg, &end);
            if (end == optarg || *end || !(time_step > 0) || time_step > 1e6) {
                fprintf(stderr, "cumulo bench: --time-step expects seconds in (0, 1e6], got '%s'\n", optarg);
                return 2;
            }
            break;
        case OPT_CAMERA:
            camera = !strcmp(optarg, "static") ? CAM_STATIC : !strcmp(optarg, "orbit") ? CAM_ORBIT
                     : !strcmp(optarg, "both") ? CAM_BOTH : -1;
            if (camera < 0) {
                fprintf(stderr, "cumulo bench: --camera expects static, orbit or both, got '%s'\n", optarg);
                return 2;
            }
            break;
        case OPT_ORBIT_STEP:
            orbit_step = strtod(optarg, &end);
            if (end == optarg || *end || !(orbit_step > 0) || orbit_step > 360) {
                fprintf(stderr, "cumulo bench: --orbit-step expects degrees in (0, 360], got '%s'\n", optarg);
                return 2;
            }
            break;
        case 'h': fputs(bench_help, stdout); return 0;
        case CLI_OPT_VERSION: cli_print_version(stdout, "cumulo"); return 0;
        case ':': fprintf(stderr, "cumulo bench: %s needs a value\n", argv[optind - 1]); return 2;
        default: fprintf(stderr, "cumulo bench: unknown option '%s'\n", argv[optind - 1]); return 2;
        }
    }
    for (; optind < argc; optind++) {
        if (o.scene_path) {
            fprintf(stderr, "cumulo bench: more than one scene given\n");
            return 2;
        }
        o.scene_path = argv[optind];
    }
    if (!o.scene_path) {
        fprintf(stderr, "usage: cumulo bench SCENE [--frames N] [--warmup N] [--size WxH] [--backend B] "
                        "[--set k=v]... [--csv FILE] [--sun-every-frame] [--sun-step DEG] [--time-step S]\n");
        return 2;
    }
    if (sun_blocks && (!sun_every_frame || camera != CAM_STATIC)) {
        fprintf(stderr, "cumulo bench: --sun-blocks needs --sun-every-frame or --sun-step, and a static camera\n");
        return 2;
    }
    cli_session s;
    int rc = cli_session_open(&s, &o);
    if (rc) {
        cli_session_close(&s);
        return rc;
    }
    char surf[256];
    s.be->describe(s.disp, surf, sizeof surf);
    const char *lp = getenv("LP_NUM_THREADS");
    printf("=======================================================\n");
    printf("    cumulo bench\n");
    printf("=======================================================\n");
    printf("    GL_VENDOR:     %s\n", cu_renderer_gl_string(s.r, 0));
    printf("    GL_RENDERER:   %s\n", cu_renderer_gl_string(s.r, 1));
    printf("    GL_VERSION:    %s\n", cu_renderer_gl_string(s.r, 2));
    printf("    Surface:       %s\n", surf);
    printf("    LP_NUM_THREADS=%s\n", lp ? lp : "(unset)");
    printf("    Timing:        wall clock per frame incl. glFinish (no GPU timer query on this path)\n");
    printf("=======================================================\n");
    double *t = malloc(sizeof(double) * (2 + CU_PASS_COUNT) * (size_t)frames), *t_still = t + frames;
    double *t_pass = t_still + frames; /* [pass * frames + frame] */
    cu_renderer_set_profiling(s.r, passes);
    if (!t) {
        cli_session_close(&s);
        return 1;
    }
    double el, az, t_scene = cu_renderer_get_time(s.r);
    cu_renderer_get_sun(s.r, &el, &az);
    float view[16], proj[16];
    double turned = 0, held_sum = 0, turning_sum = 0; /* --sun-blocks: degrees turned so far, the two kinds' sums */
    int held_n = 0, turning_n = 0;
    for (int i = 0; i < warmup + frames; i++) {
        int held = sun_blocks && i / sun_blocks % 2 == 1, settled = cu_renderer_settled(s.r);
        if (sun_every_frame && !held) {
            cu_error e;
            cu_renderer_set_sun(s.r, el, az + turned, &e);
            turned += sun_step;
        }
        if (time_step > 0) {
            cu_error e;
            if (cu_renderer_set_time(s.r, t_scene + time_step * i, &e)) {
                fprintf(stderr, "cumulo: %s\n", e.msg);
                rc = 1;
            }
        }
        int moving = camera != CAM_STATIC;
        if (moving && orbit_pose(s.scene, orbit_step * i, (double)s.width / s.height, view, proj))
            rc = 1;
        for (int pass = 0; pass < (camera == CAM_BOTH ? 2 : 1) && !rc; pass++) {
            double t0 = now_ms();
            if (cli_session_render_view(&s, moving ? view : NULL, moving ? proj : NULL))
                rc = 1;
            double dt = now_ms() - t0;
            if (i >= warmup)
                (pass ? t_still : t)[i - warmup] = dt;
            if (i >= warmup && sun_blocks && !held)
                turning_sum += dt, turning_n++;
            else if (i >= warmup && sun_blocks && settled) /* a held frame with nothing left to catch up */
                held_sum += dt, held_n++;
            double ms[CU_PASS_COUNT];
            if (passes && !pass && i >= warmup && !cu_renderer_pass_times(s.r, ms))
                for (int k = 0; k < CU_PASS_COUNT; k++)
                    t_pass[k * frames + i - warmup] = ms[k];
        }
        if (rc) {
            free(t);
            cli_session_close(&s);
            return 1;
        }
    }
    int i95 = (int)(0.95 * (frames - 1) + 0.5);
    double mean = 0; /* what work spread over frames (a map a band a frame, a closure a degree) costs on average */
    for (int i = 0; i < frames; i++)
        mean += t[i] / frames;
    double med = median(t, frames), p95 = t[i95]; /* median() sorts */
    double still_med = camera == CAM_BOTH ? median(t_still, frames) : 0;
    double still_p95 = camera == CAM_BOTH ? t_still[i95] : 0;
    char opts[1024];
    int n = snprintf(opts, sizeof opts, "size=%dx%d", s.width, s.height);
    for (int i = 0; i < o.nsets && n < (int)sizeof opts - 2; i++)
        n += snprintf(opts + n, sizeof opts - (size_t)n, ":%s", o.sets[i]);
    if (sun_every_frame && n < (int)sizeof opts - 40)
        n += snprintf(opts + n, sizeof opts - (size_t)n, sun_step == 0.01 ? ":sun-every-frame" : ":sun-step=%g",
                      sun_step);
    if (time_step > 0 && n < (int)sizeof opts - 40)
        n += snprintf(opts + n, sizeof opts - (size_t)n, ":time-step=%g", time_step);
    if (camera != CAM_STATIC && n < (int)sizeof opts - 40)
        snprintf(opts + n, sizeof opts - (size_t)n, ":camera=orbit:orbit-step=%g", orbit_step);
    const char *base = strrchr(o.scene_path, '/');
    base = base ? base + 1 : o.scene_path;
    printf("[%s] %s: FPS: %.1f FrameTime: %.3f ms p95: %.3f ms mean: %.3f ms frames: %d\n", base, opts, 1000.0 / med,
           med, p95, mean, frames);
    if (passes) { /* each pass's median over the frames (the medians need not add up to the frame's) */
        printf("[%s] %s: passes (median ms, %s):", base, opts, cu_renderer_profiling_clock(s.r));
        for (int k = 0; k < CU_PASS_COUNT; k++)
            printf(" %s=%.3f", cu_pass_name(k), median(t_pass + (size_t)k * frames, frames));
        printf("\n");
    }
    int bd, bg;
    double bms;
    if (cu_renderer_budget(s.r, &bd, &bg, &bms) == 0) /* where the frame budget ended */
        printf("[%s] %s: budget: clouds at 1/%d resolution, temporal grid %d, last median %.3f ms (timer's)\n", base,
               opts, bd, bg, bms);
    if (sun_blocks && (!turning_n || !held_n)) {
        fprintf(stderr, "cumulo bench: --sun-blocks %d: %s; more frames or longer blocks\n", sun_blocks,
                turning_n ? "the picture never settled in a held block" : "no turning frame was measured");
        rc = 1;
    } else if (sun_blocks) {
        printf("[%s] %s:sun-blocks=%d: turning: mean %.3f ms (%d frames) held: mean %.3f ms (%d settled frames)\n",
               base, opts, sun_blocks, turning_sum / turning_n, turning_n, held_sum / held_n, held_n);
        printf("turning/held mean frame time: %.3f (blocks of %d frames, interleaved)\n",
               (turning_sum / turning_n) / (held_sum / held_n), sun_blocks);
    }
    if (camera == CAM_BOTH) {
        printf("[%s] %s:unmoved: FPS: %.1f FrameTime: %.3f ms p95: %.3f ms frames: %d\n", base, opts,
               1000.0 / still_med, still_med, still_p95, frames);
        printf("moving/unmoved median frame time: %.3f (the same poses, interleaved)\n", med / still_med);
    }
    if (csv) {
        FILE *f = fopen(csv, "a");
        int ok = f != NULL;
        if (ok) {
            fseek(f, 0, SEEK_END);
            if (ftell(f) == 0)
                ok = fprintf(f, "scene,options,frames,median_ms,p95_ms,fps,renderer\n") > 0;
            ok = ok && fprintf(f, "%s,%s,%d,%.3f,%.3f,%.2f,\"%s\"\n", base, opts, frames, med, p95, 1000.0 / med,
                               cu_renderer_gl_string(s.r, 1)) > 0;
            ok = fclose(f) == 0 && ok;
        }
        if (!ok) {
            fprintf(stderr, "cumulo bench: cannot write %s: %s\n", csv, strerror(errno));
            rc = 1;
        }
    }
    free(t);
    cli_session_close(&s);
    return rc;
}
