/* app/cmd_render.c: `cumulo render`: one frame to a PNG (tone-mapped sRGB) or PFM (linear radiance). */
#include "commands.h"
#include "session.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static int ends_with(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && strcmp(s + a - b, suffix) == 0;
}

static const char render_help[] =
    "usage: cumulo render SCENE -o OUT.png|OUT.pfm [options]\n"
    "Renders one frame of SCENE headless: OUT.png tone-mapped 8-bit sRGB, OUT.pfm linear radiance (float).\n"
    "  -o, --output FILE      the image to write (.png or .pfm); with --frames, a pattern with one %d\n"
    "                         (%05d: zero-padded), e.g. frames/%05d.png\n"
    "  --frames N             a sequence of N frames (1..1000000), frame k at the scene time + k / fps\n"
    "  --fps F                frames per second of scene time (default 30)\n"
    "  --progress             a progress bar on stderr (default: when stderr is a terminal and N > 1)\n"
    CLI_COMMON_HELP;

/* A sequence's file name pattern: exactly one %d, optionally with a width and zero flag (%05d), and %% for a
 * percent sign; anything else could make snprintf read arguments that are not there. */
static int pattern_ok(const char *p)
{
    int ints = 0;
    for (; *p; p++) {
        if (*p != '%')
            continue;
        p++;
        if (*p == '%')
            continue;
        if (*p == '0')
            p++;
        int digits = 0;
        while (*p >= '0' && *p <= '9' && digits < 3) {
            p++;
            digits++;
        }
        if (*p != 'd')
            return 0;
        ints++;
    }
    return ints == 1;
}

static void progress(int done, int n, double elapsed)
{
    int w = 30, fill = n > 0 ? (int)((long)w * done / n) : w;
    double per = done > 0 ? elapsed / done : 0, left = per * (n - done);
    fprintf(stderr, "\r[%.*s%*s] %d/%d frames, %.2f s/frame, %.0f s left ", fill,
            "##############################", w - fill, "", done, n, per, left);
    if (done == n)
        fputc('\n', stderr);
    fflush(stderr);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int write_frame(cli_session *s, const char *out, int pfm)
{
    cu_error err = {"cannot read the frame back"};
    int rc = 0;
    if (pfm) {
        float *px = malloc(sizeof(float) * 3 * (size_t)s->width * s->height);
        if (!px || cli_session_read_rgbf(s, px) || cu_write_pfm(out, px, s->width, s->height, &err)) {
            fprintf(stderr, "cumulo: %s\n", px ? err.msg : "out of memory");
            rc = 1;
        }
        free(px);
    } else {
        uint8_t *px = malloc(4 * (size_t)s->width * s->height);
        if (!px || cli_session_read_rgba8(s, px) || cu_write_png(out, px, s->width, s->height, &err)) {
            fprintf(stderr, "cumulo: %s\n", px ? err.msg : "out of memory");
            rc = 1;
        }
        free(px);
    }
    return rc;
}

int cmd_render(int argc, char **argv)
{
    enum { OPT_FRAMES = 0x200, OPT_FPS, OPT_PROGRESS };
    static const struct option longopts[] = {CLI_COMMON_LONGOPTS, {"output", required_argument, NULL, 'o'},
                                             {"frames", required_argument, NULL, OPT_FRAMES},
                                             {"fps", required_argument, NULL, OPT_FPS},
                                             {"progress", no_argument, NULL, OPT_PROGRESS}, {NULL, 0, NULL, 0}};
    cli_opts o = {0};
    const char *out = NULL;
    long frames = 1;
    double fps = 30;
    int bar = -1;
    int c;
    opterr = 0;
    optind = 1;
    while ((c = getopt_long(argc, argv, ":o:vh", longopts, NULL)) != -1) {
        int k = cli_common_getopt(&o, c, optarg, "cumulo render");
        if (k < 0)
            return 2;
        if (k)
            continue;
        switch (c) {
        case 'o': out = optarg; break;
        case OPT_FRAMES:
            if (cli_parse_counts(optarg, 0, 1, 1, 1000000, &frames)) {
                fprintf(stderr, "cumulo render: --frames expects 1..1000000, got '%s'\n", optarg);
                return 2;
            }
            break;
        case OPT_FPS: {
            char *end;
            fps = strtod(optarg, &end);
            if (end == optarg || *end || !(fps > 0 && fps <= 1e6)) {
                fprintf(stderr, "cumulo render: --fps expects a number in (0, 1e6], got '%s'\n", optarg);
                return 2;
            }
            break;
        }
        case OPT_PROGRESS: bar = 1; break;
        case 'h': fputs(render_help, stdout); return 0;
        case CLI_OPT_VERSION: cli_print_version(stdout, "cumulo"); return 0;
        case ':': fprintf(stderr, "cumulo render: %s needs a value\n", argv[optind - 1]); return 2;
        default: fprintf(stderr, "cumulo render: unknown option '%s'\n", argv[optind - 1]); return 2;
        }
    }
    for (; optind < argc; optind++) {
        if (o.scene_path) {
            fprintf(stderr, "cumulo render: more than one scene given ('%s')\n", argv[optind]);
            return 2;
        }
        o.scene_path = argv[optind];
    }
    if (!o.scene_path || !out) {
        fprintf(stderr, "usage: cumulo render SCENE -o OUT.png|OUT.pfm [--size WxH] [--backend egl|osmesa] "
                        "[--set section.key=value]... (cumulo render --help)\n");
        return 2;
    }
    int pfm = ends_with(out, ".pfm");
    if (!pfm && !ends_with(out, ".png")) {
        fprintf(stderr, "cumulo render: output '%s' must end in .png or .pfm\n", out);
        return 2;
    }
    if (frames > 1 && !pattern_ok(out)) {
        fprintf(stderr, "cumulo render: with --frames, the output '%s' needs exactly one %%d (e.g. frames/%%05d.png)\n",
                out);
        return 2;
    }
    if (bar < 0)
        bar = frames > 1 && isatty(2);
    o.linear = pfm;
    cli_session s;
    int rc = cli_session_open(&s, &o);
    if (rc) {
        cli_session_close(&s);
        return rc;
    }
    double t0 = cu_renderer_get_time(s.r), start = now_s();
    char name[4096];
    for (long k = 0; k < frames && rc == 0; k++) {
        cu_error err;
        if (frames > 1 && cu_renderer_set_time(s.r, t0 + (double)k / fps, &err)) {
            fprintf(stderr, "cumulo: frame %ld: %s\n", k, err.msg);
            rc = 1;
            break;
        }
        if ((rc = cli_session_render(&s)) != 0)
            break;
        if (frames > 1) {
            int n = snprintf(name, sizeof name, out, (int)k); /* pattern_ok: one %d, nothing else */
            if (n < 0 || n >= (int)sizeof name) {
                fprintf(stderr, "cumulo render: output name too long\n");
                rc = 2;
                break;
            }
        } else {
            snprintf(name, sizeof name, "%s", out);
        }
        rc = write_frame(&s, name, pfm);
        if (bar)
            progress((int)k + 1, (int)frames, now_s() - start);
    }
    if (rc == 0 && frames == 1)
        printf("wrote %s (%dx%d, %s)\n", out, s.width, s.height, s.be->name);
    else if (rc == 0)
        printf("wrote %ld frames %s (%dx%d, %s), scene time %g .. %g s\n", frames, out, s.width, s.height,
               s.be->name, t0, t0 + (double)(frames - 1) / fps);
    cli_session_close(&s);
    return rc;
}
