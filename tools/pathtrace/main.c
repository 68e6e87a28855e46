/* tools/pathtrace/main.c: build/cumulo-pt, the command line of the reference path tracer (usage in README.md). */
#include "image.h"
#include "pt.h"
#include <errno.h>
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
    "usage: cumulo-pt SCENE -o OUT.pfm [--spp N] [--threads N] [--seed S] [--size WxH] [--set section.key=value]...\n"
    "                 [--max-depth N] [--aa] [--mode radiance|transmittance] [--peak-mis P] [--quiet]\n"
    "                 [--dump-density FILE [--grid NX,NY,NZ]]\n";

/* Whole-string unsigned integer in [lo, hi]; 0 on success. */
static int parse_u64(const char *s, unsigned long long lo, unsigned long long hi, unsigned long long *out)
{
    if (!s || !*s || *s == '-' || *s == '+' || *s == ' ')
        return 1;
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (errno || *end || v < lo || v > hi)
        return 1;
    *out = v;
    return 0;
}

static int ends_with(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && strcmp(s + a - b, suffix) == 0;
}

static int bad(const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "cumulo-pt: ");
    fprintf(stderr, fmt, a, b);
    fprintf(stderr, "\n");
    return 2;
}

int main(int argc, char **argv)
{
    const char *scene_path = NULL, *out = NULL, *dump = NULL, *sets[MAX_SETS];
    int nsets = 0, quiet = 0, aa = 0, width = 0, height = 0, grid[3] = {128, 128, 128}, have_grid = 0;
    unsigned long long spp = 16, seed = 1, max_depth = 1000000, threads = 0;
    pt_mode mode = PT_MODE_RADIANCE;
    double peak_mis = PT_GUIDE_DEFAULT;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int takes = strcmp(a, "-o") == 0 || strcmp(a, "--spp") == 0 || strcmp(a, "--threads") == 0 ||
                    strcmp(a, "--seed") == 0 || strcmp(a, "--size") == 0 || strcmp(a, "--set") == 0 ||
                    strcmp(a, "--max-depth") == 0 || strcmp(a, "--mode") == 0 || strcmp(a, "--dump-density") == 0 ||
                    strcmp(a, "--grid") == 0 || strcmp(a, "--peak-mis") == 0;
        if (takes && i + 1 >= argc)
            return bad("%s needs a value%s", a, "");
        const char *v = takes ? argv[++i] : NULL;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(usage, stdout);
            return 0;
        } else if (strcmp(a, "-o") == 0) {
            out = v;
        } else if (strcmp(a, "--spp") == 0) {
            if (parse_u64(v, 1, 100000000, &spp))
                return bad("--spp expects a count from 1 to 100000000, got '%s'%s", v, "");
        } else if (strcmp(a, "--threads") == 0) {
            if (parse_u64(v, 1, 256, &threads))
                return bad("--threads expects a count from 1 to 256, got '%s'%s", v, "");
        } else if (strcmp(a, "--seed") == 0) {
            if (parse_u64(v, 0, 18446744073709551615ull, &seed))
                return bad("--seed expects an unsigned 64-bit integer, got '%s'%s", v, "");
        } else if (strcmp(a, "--max-depth") == 0) {
            if (parse_u64(v, 0, 1000000000, &max_depth))
                return bad("--max-depth expects a count from 0 to 1000000000, got '%s'%s", v, "");
        } else if (strcmp(a, "--size") == 0) {
            char tail;
            if (sscanf(v, "%dx%d%c", &width, &height, &tail) != 2 || width < 1 || height < 1 || width > 16384 ||
                height > 16384)
                return bad("--size expects WxH with 1..16384, got '%s'%s", v, "");
        } else if (strcmp(a, "--set") == 0) {
            if (nsets == MAX_SETS)
                return bad("at most 64 --set options%s%s", "", "");
            sets[nsets++] = v;
        } else if (strcmp(a, "--mode") == 0) {
            if (strcmp(v, "radiance") == 0)
                mode = PT_MODE_RADIANCE;
            else if (strcmp(v, "transmittance") == 0)
                mode = PT_MODE_TRANSMITTANCE;
            else
                return bad("--mode must be radiance or transmittance, got '%s'%s", v, "");
        } else if (strcmp(a, "--peak-mis") == 0) {
            char *end;
            errno = 0;
            peak_mis = strtod(v, &end);
            if (end == v || *end || errno || !(peak_mis >= 0 && peak_mis <= 1))
                return bad("--peak-mis expects a probability in [0, 1], got '%s'%s", v, "");
        } else if (strcmp(a, "--dump-density") == 0) {
            dump = v;
        } else if (strcmp(a, "--grid") == 0) {
            char tail;
            if (sscanf(v, "%d,%d,%d%c", &grid[0], &grid[1], &grid[2], &tail) != 3 || grid[0] < 1 || grid[1] < 1 ||
                grid[2] < 1 || grid[0] > 4096 || grid[1] > 4096 || grid[2] > 4096 ||
                (double)grid[0] * grid[1] * grid[2] > 1073741824.0)
                return bad("--grid expects NX,NY,NZ with 1..4096 each and at most 2^30 voxels, got '%s'%s", v, "");
            have_grid = 1;
        } else if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0) {
            quiet = 1;
        } else if (strcmp(a, "--aa") == 0) {
            aa = 1;
        } else if (a[0] == '-' && a[1]) {
            return bad("unknown option '%s'%s", a, "");
        } else if (!scene_path) {
            scene_path = a;
        } else {
            return bad("more than one scene given ('%s')%s", a, "");
        }
    }
    if (!scene_path || (!out && !dump)) {
        fputs(usage, stderr);
        return 2;
    }
    if (out && !ends_with(out, ".pfm"))
        return bad("output '%s' must end in .pfm%s", out, "");
    if (have_grid && !dump)
        return bad("--grid only applies to --dump-density%s%s", "", "");

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
        char perr[512], sp[4200];
        snprintf(sp, sizeof sp, "%s.stderr.pfm", out);
        if (rc == 0 && (cu_pfm_write(out, mean, s->width, s->height, perr, sizeof perr) ||
                        cu_pfm_write(sp, se, s->width, s->height, perr, sizeof perr))) {
            fprintf(stderr, "cumulo-pt: %s\n", perr);
            rc = 1;
        }
        if (rc == 0) {
            double secs = (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec);
            printf("wrote %s and %s (%dx%d, %llu spp, seed %llu, %llu threads, %.2f s; %.2f scattering events and "
                   "%.1f density lookups per path; %llu of %llu paths cut at max depth %llu)\n",
                   out, sp, s->width, s->height, spp, seed, threads, secs,
                   k.paths ? (double)k.scatters / k.paths : 0.0, k.paths ? (double)k.density_evals / k.paths : 0.0,
                   (unsigned long long)k.truncated, (unsigned long long)k.paths, max_depth);
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
