/* tools/pathtrace/main.c: build/cumulo-pt, the command line of the reference path tracer (usage in README.md). */
#include "error.h"
#include "image.h"
#include "pt.h"
#include "version.h"
#include "../tool_cli.h"
#include <errno.h>
#include <getopt.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#ifndef CU_INSTALL_DATA_DIR
#define CU_INSTALL_DATA_DIR "/usr/local/share/cumulo/data"
#endif
#define MAX_SETS 64

static const char usage[] =
    "usage: cumulo-pt SCENE -o OUT.pfm [options]\n"
    "       cumulo-pt SCENE --dump-density FILE [--grid NX,NY,NZ]\n"
    "Renders SCENE by volumetric path tracing (all orders of scattering) into OUT.pfm, the mean radiance per pixel,\n"
    "and OUT.pfm.stderr.pfm, its standard error (see tools/pathtrace/README.md).\n"
    "options:\n"
    "  -o OUT.pfm               output image (must end in .pfm)\n"
    "  --spp N                  samples per pixel, 1..100000000 (default 16)\n"
    "  --threads N              worker threads, 1..256 (default: one per online CPU)\n"
    "  --seed S                 random seed, an unsigned 64-bit integer (default 1)\n"
    "  --size WxH               image size, 1..16384 each (default: the scene's [output] size)\n"
    "  --set section.key=value  override a scene key, as cumulo --set does (at most 64)\n"
    "  --max-depth N            scattering events per path before it is cut, 0..1000000000 (default 1000000)\n"
    "  --max-steps N            tracking steps per path (collisions, null collisions, shadow rays) before it\n"
    "                           is cut, 1..1000000000000 (default 100000); cut paths are counted and reported\n"
    "  --aa                     jitter inside each pixel (box filter) instead of the pixel centre\n"
    "  --mode M                 radiance (default) or transmittance, exp(-tau) along each camera ray\n"
    "  --peak-mis P             probability per scattering event of the forward-peak sun strategy, [0, 1]\n"
    "                           (default 1; changes the noise, never the expectation)\n"
    "  --dump-density FILE      write the k_e grid the tracer sees to FILE and FILE.txt\n"
    "  --grid NX,NY,NZ          that grid, 1..4096 each, at most 2^30 voxels (default 128,128,128)\n"
    "  -q, --quiet              no progress bar, no summary line\n"
    "  -h, --help               this text\n"
    "  --version                the version\n"
    "Argument errors exit 2; a bad scene, a bad --set and unwritable outputs exit 1.\n";

/* Whole-string unsigned integer in [lo, hi]; 0 on success. */
static int parse_u64(const char *s, unsigned long long lo, unsigned long long hi, unsigned long long *out)
{
    return tool_parse_uints(s, 0, 1, lo, hi, out);
}

static int ends_with(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && strcmp(s + a - b, suffix) == 0;
}

/* A usage error: one line, exit status 2. */
static int bad(const char *fmt, ...) CU_PRINTF(1, 2);
static int bad(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "cumulo-pt: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    return 2;
}

int main(int argc, char **argv)
{
    const char *scene_path = NULL, *out = NULL, *dump = NULL, *sets[MAX_SETS];
    int nsets = 0, quiet = 0, aa = 0, width = 0, height = 0, grid[3] = {128, 128, 128}, have_grid = 0;
    unsigned long long spp = 16, seed = 1, max_depth = 1000000, threads = 0, max_steps = PT_MAX_STEPS;
    pt_mode mode = PT_MODE_RADIANCE;
    double peak_mis = PT_GUIDE_DEFAULT;
    enum { O_SPP = 256, O_THREADS, O_SEED, O_SIZE, O_SET, O_MAX_DEPTH, O_MODE, O_PEAK_MIS, O_DUMP, O_GRID, O_AA,
           O_VERSION, O_MAX_STEPS };
    static const struct option opts[] = {
        {"spp", required_argument, NULL, O_SPP},           {"threads", required_argument, NULL, O_THREADS},
        {"seed", required_argument, NULL, O_SEED},         {"size", required_argument, NULL, O_SIZE},
        {"set", required_argument, NULL, O_SET},           {"max-depth", required_argument, NULL, O_MAX_DEPTH},
        {"mode", required_argument, NULL, O_MODE},         {"peak-mis", required_argument, NULL, O_PEAK_MIS},
        {"dump-density", required_argument, NULL, O_DUMP}, {"grid", required_argument, NULL, O_GRID},
        {"aa", no_argument, NULL, O_AA},                   {"quiet", no_argument, NULL, 'q'},
        {"help", no_argument, NULL, 'h'},                  {"version", no_argument, NULL, O_VERSION},
        {"max-steps", required_argument, NULL, O_MAX_STEPS},
        {NULL, 0, NULL, 0}};
    opterr = 0;
    for (int o; (o = getopt_long(argc, argv, ":o:qh", opts, NULL)) != -1;) {
        const char *v = optarg;
        char *end;
        unsigned long long wh[2], g3[3];
        switch (o) {
        case 'h':
            fputs(usage, stdout);
            return 0;
        case O_VERSION:
            printf("cumulo-pt %s (%s)\n", CU_VERSION, CU_GIT_DESCRIBE);
            return 0;
        case ':':
            return bad("%s needs a value", argv[optind - 1]);
        case '?':
            return bad("unknown option '%s'", argv[optind - 1]);
        case 'o':
            out = v;
            break;
        case O_SPP:
            if (parse_u64(v, 1, 100000000, &spp))
                return bad("--spp expects a count from 1 to 100000000, got '%s'", v);
            break;
        case O_THREADS:
            if (parse_u64(v, 1, 256, &threads))
                return bad("--threads expects a count from 1 to 256, got '%s'", v);
            break;
        case O_SEED:
            if (parse_u64(v, 0, 18446744073709551615ull, &seed))
                return bad("--seed expects an unsigned 64-bit integer, got '%s'", v);
            break;
        case O_MAX_DEPTH:
            if (parse_u64(v, 0, 1000000000, &max_depth))
                return bad("--max-depth expects a count from 0 to 1000000000, got '%s'", v);
            break;
        case O_MAX_STEPS:
            if (parse_u64(v, 1, 1000000000000ull, &max_steps))
                return bad("--max-steps expects a count from 1 to 1000000000000, got '%s'", v);
            break;
        case O_SIZE:
            if (tool_parse_uints(v, 'x', 2, 1, 16384, wh))
                return bad("--size expects WxH with 1..16384, got '%s'", v);
            width = (int)wh[0];
            height = (int)wh[1];
            break;
        case O_SET:
            if (nsets == MAX_SETS)
                return bad("at most %d --set options", MAX_SETS);
            sets[nsets++] = v;
            break;
        case O_MODE:
            if (strcmp(v, "radiance") == 0)
                mode = PT_MODE_RADIANCE;
            else if (strcmp(v, "transmittance") == 0)
                mode = PT_MODE_TRANSMITTANCE;
            else
                return bad("--mode must be radiance or transmittance, got '%s'", v);
            break;
        case O_PEAK_MIS:
            errno = 0;
            peak_mis = strtod(v, &end);
            if (end == v || *end || errno || !(peak_mis >= 0 && peak_mis <= 1))
                return bad("--peak-mis expects a probability in [0, 1], got '%s'", v);
            break;
        case O_DUMP:
            dump = v;
            break;
        case O_GRID:
            if (tool_parse_uints(v, ',', 3, 1, 4096, g3) || g3[0] * g3[1] * g3[2] > 1073741824ull)
                return bad("--grid expects NX,NY,NZ with 1..4096 each and at most 2^30 voxels, got '%s'", v);
            for (int i = 0; i < 3; i++)
                grid[i] = (int)g3[i];
            have_grid = 1;
            break;
        case 'q':
            quiet = 1;
            break;
        case O_AA:
            aa = 1;
            break;
        }
    }
    /* getopt_long has moved the operands to the end */
    for (; optind < argc; optind++) {
        if (scene_path)
            return bad("more than one scene given ('%s')", argv[optind]);
        scene_path = argv[optind];
    }
    if (!scene_path || (!out && !dump))
        return bad("needs SCENE and -o OUT.pfm or --dump-density FILE (usage: cumulo-pt --help)");
    if (out && !ends_with(out, ".pfm"))
        return bad("output '%s' must end in .pfm", out);
    if (have_grid && !dump)
        return bad("--grid only applies to --dump-density");

    cu_scene *s;
    cu_error e;
    if (cu_scene_load(&s, scene_path, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return 1;
    }
    for (int i = 0; i < nsets; i++)
        if (cu_scene_set(s, sets[i], &e)) {
            fprintf(stderr, "%s\n", e.msg);
            cu_scene_free(s);
            return 1;
        }
    if (width) {
        s->width = width;
        s->height = height;
    }
    /* Tables as the cumulo program finds them: $CUMULO_DATA_DIR, ./data (a source tree), the installed copy. */
    const char *dd = getenv("CUMULO_DATA_DIR");
    struct stat sb;
    if (!dd)
        dd = stat("data/mie_cloud.tbl", &sb) == 0 ? "data" : CU_INSTALL_DATA_DIR;
    pt_ctx *c = malloc(sizeof *c);
    if (!c || pt_ctx_init(c, s, dd, &e)) {
        fprintf(stderr, "cumulo-pt: %s\n", c ? e.msg : "out of memory");
        free(c);
        cu_scene_free(s);
        return 1;
    }
    c->max_depth = (int)max_depth;
    c->max_steps = max_steps;
    c->guide = peak_mis;
    int rc = 0;
    if (dump) {
        if (pt_dump_density(c, dump, grid[0], grid[1], grid[2], PT_NOISE_SEED, &e)) {
            fprintf(stderr, "cumulo-pt: %s\n", e.msg);
            rc = 1;
        } else if (!quiet) {
            printf("wrote %s and %s.txt (%dx%dx%d float32 k_e)\n", dump, dump, grid[0], grid[1], grid[2]);
        }
    }
    if (out && rc == 0) {
        if (!threads) {
            long n = sysconf(_SC_NPROCESSORS_ONLN);
            threads = n < 1 ? 1 : n > 256 ? 256 : (unsigned long long)n;
        }
        size_t np = 3 * (size_t)s->width * s->height;
        float *mean = malloc(sizeof(float) * np), *se = malloc(sizeof(float) * np);
        pt_render_opts o = {s->width, s->height, (int)spp, (int)threads, seed, aa, mode, !quiet};
        pt_counters k;
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        if (!mean || !se) {
            fprintf(stderr, "cumulo-pt: out of memory for a %dx%d image\n", s->width, s->height);
            rc = 1;
        } else if (pt_render(c, &o, mean, se, &k, &e)) {
            fprintf(stderr, "cumulo-pt: %s\n", e.msg);
            rc = 1;
        }
        clock_gettime(CLOCK_MONOTONIC, &t1);
        cu_error perr;
        char sp[4200];
        snprintf(sp, sizeof sp, "%s.stderr.pfm", out);
        if (rc == 0 && (cu_write_pfm(out, mean, s->width, s->height, &perr) ||
                        cu_write_pfm(sp, se, s->width, s->height, &perr))) {
            fprintf(stderr, "cumulo-pt: %s\n", perr.msg);
            rc = 1;
        }
        if (rc == 0) {
            double secs = (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec);
            printf("wrote %s and %s (%dx%d, %llu spp, seed %llu, %llu threads, %.2f s; %.2f scattering events and "
                   "%.1f density lookups per path; %llu of %llu paths cut at max depth %llu)\n",
                   out, sp, s->width, s->height, spp, seed, threads, secs,
                   k.paths ? (double)k.scatters / k.paths : 0.0, k.paths ? (double)k.density_evals / k.paths : 0.0,
                   (unsigned long long)k.truncated, (unsigned long long)k.paths, max_depth);
            if (k.step_capped) /* a cut path is biased low: say so even with -q */
                fprintf(stderr, "cumulo-pt: warning: %llu of %llu paths cut at --max-steps %llu (the image is biased "
                        "dark where they were)\n", (unsigned long long)k.step_capped, (unsigned long long)k.paths,
                        max_steps);
            if (spp < 2)
                fprintf(stderr, "cumulo-pt: warning: 1 sample per pixel gives no error estimate (%s is zero)\n", sp);
        }
        free(mean);
        free(se);
    }
    pt_ctx_free(c);
    free(c);
    cu_scene_free(s);
    return rc;
}
