/* src/cli/cmd_bench.c: `cumulo bench`: renders N frames after warm-up and prints glmark2-style lines with the
 * median and 95th percentile frame time (wall clock per frame including glFinish); optional CSV. */
#include "commands.h"
#include "session.h"
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

int cmd_bench(int argc, char **argv)
{
    cli_opts o = {0};
    int frames = 30, warmup = 3, sun_every_frame = 0;
    double sun_step = 0.01; /* degrees of azimuth per frame with --sun-every-frame: a knob turned slowly */
    const char *csv = NULL;
    for (int i = 1; i < argc; i++) {
        int c = cli_common_option(&o, argc, argv, &i);
        if (c < 0)
            return 2;
        if (c)
            continue;
        if ((strcmp(argv[i], "--frames") == 0 || strcmp(argv[i], "--warmup") == 0) && i + 1 < argc) {
            char *end;
            long v = strtol(argv[i + 1], &end, 10);
            if (*end || v < (argv[i][2] == 'f' ? 1 : 0) || v > 1000000) {
                fprintf(stderr, "cumulo bench: %s expects a count, got '%s'\n", argv[i], argv[i + 1]);
                return 2;
            }
            if (argv[i][2] == 'f') frames = (int)v; else warmup = (int)v;
            i++;
        } else if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
            csv = argv[++i];
        } else if (strcmp(argv[i], "--sun-step") == 0 && i + 1 < argc) {
            char *end;
            sun_step = strtod(argv[i + 1], &end);
            if (*end || !(sun_step > 0) || sun_step > 360) {
                fprintf(stderr, "cumulo bench: --sun-step expects degrees in (0, 360], got '%s'\n", argv[i + 1]);
                return 2;
            }
            sun_every_frame = 1;
            i++;
        } else if (strcmp(argv[i], "--sun-every-frame") == 0) {
            sun_every_frame = 1; /* measure the sun pass too, as when a knob turns the sun */
        } else if (argv[i][0] == '-') {
            fprintf(stderr, "cumulo bench: unknown option '%s'\n", argv[i]);
            return 2;
        } else if (!o.scene_path) {
            o.scene_path = argv[i];
        } else {
            fprintf(stderr, "cumulo bench: more than one scene given\n");
            return 2;
        }
    }
    if (!o.scene_path) {
        fprintf(stderr, "usage: cumulo bench SCENE [--frames N] [--warmup N] [--size WxH] [--backend B] "
                        "[--set k=v]... [--csv FILE] [--sun-every-frame] [--sun-step DEG]\n");
        return 2;
    }
    cli_session s;
    if (cli_session_open(&s, &o)) {
        cli_session_close(&s);
        return 1;
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
    double *t = malloc(sizeof(double) * (size_t)frames);
    if (!t) {
        cli_session_close(&s);
        return 1;
    }
    double el, az;
    cu_renderer_get_sun(s.r, &el, &az);
    for (int i = 0; i < warmup + frames; i++) {
        if (sun_every_frame) {
            cu_error e;
            cu_renderer_set_sun(s.r, el, az + sun_step * i, &e);
        }
        double t0 = now_ms();
        if (cli_session_render(&s)) {
            free(t);
            cli_session_close(&s);
            return 1;
        }
        if (i >= warmup)
            t[i - warmup] = now_ms() - t0;
    }
    qsort(t, (size_t)frames, sizeof *t, cmp_double);
    double med = frames % 2 ? t[frames / 2] : 0.5 * (t[frames / 2 - 1] + t[frames / 2]);
    int i95 = (int)(0.95 * (frames - 1) + 0.5);
    double p95 = t[i95];
    char opts[1024];
    int n = snprintf(opts, sizeof opts, "size=%dx%d", s.width, s.height);
    for (int i = 0; i < o.nsets && n < (int)sizeof opts - 2; i++)
        n += snprintf(opts + n, sizeof opts - (size_t)n, ":%s", o.sets[i]);
    if (sun_every_frame && n < (int)sizeof opts - 40)
        snprintf(opts + n, sizeof opts - (size_t)n, sun_step == 0.01 ? ":sun-every-frame" : ":sun-step=%g", sun_step);
    const char *base = strrchr(o.scene_path, '/');
    base = base ? base + 1 : o.scene_path;
    printf("[%s] %s: FPS: %.1f FrameTime: %.3f ms p95: %.3f ms frames: %d\n", base, opts, 1000.0 / med, med, p95,
           frames);
    if (csv) {
        FILE *f = fopen(csv, "a");
        if (!f) {
            fprintf(stderr, "cumulo bench: cannot write %s\n", csv);
        } else {
            fseek(f, 0, SEEK_END);
            if (ftell(f) == 0)
                fprintf(f, "scene,options,frames,median_ms,p95_ms,fps,renderer\n");
            fprintf(f, "%s,%s,%d,%.3f,%.3f,%.2f,\"%s\"\n", base, opts, frames, med, p95, 1000.0 / med,
                    cu_renderer_gl_string(s.r, 1));
            fclose(f);
        }
    }
    free(t);
    cli_session_close(&s);
    return 0;
}
