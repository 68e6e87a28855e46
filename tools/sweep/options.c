/* tools/sweep/options.c: cumulo-sweep's command line (getopt_long) and the list of views. Usage errors print one
 * line on stderr and give exit status 2; --help and --version print on stdout and give 0. */
#include "sweep.h"
#include "version.h"
#include "../tool_cli.h"
#include <getopt.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* the six views the sweep began with, and the four written for issue 14 before any tuning (Henyey-Greenstein, a
 * constant sky: what an outside comparison rendered; --methods's views) */
#define DEFAULT_SCENES "cumulus,silver_lining,sweep_thick_below,glory,inside,low_sun,sweep_cumulus_hg," \
    "sweep_silver_lining_hg,sweep_below_hg,sweep_low_sun_hg"
#define DEFAULT_SUN_STEP 0.6 /* degrees a timed frame: a knob turned fast, 18 degrees a second at 30 frames */
#define QUICK_SCENES "cumulus,silver_lining"
#define METHODS_SCENES "sweep_cumulus_hg,sweep_silver_lining_hg,sweep_below_hg,sweep_low_sun_hg"
#define METHODS_BASELINE "scenes/sweep_cumulus_hg.scene"
#define FIT_SCENES "scenes/fit/sphere_side.scene,scenes/fit/tower_backlit.scene,scenes/fit/layer_below.scene," \
    "scenes/fit/cluster_front.scene"
#define FIT_SPP 1024

static const char HELP[] =
    "usage: cumulo-sweep [OPTION]...\n"
    "Speed against accuracy of the real-time renderer: every knob changed alone from `high`, timed and compared with\n"
    "path-traced references, then presets chosen within time budgets (README \"Speed against accuracy\"). Writes\n"
    "DIR/sweep.csv, DIR/sweep.md, DIR/presets.txt and DIR/pareto.dat (and DIR/pareto.png with gnuplot).\n"
    "\n"
    "  --scenes LIST        comma-separated views: NAME is scenes/NAME.scene, anything with '/' or ending in .scene\n"
    "                       a path (default cumulus,silver_lining,sweep_thick_below,glory,inside,low_sun and\n"
    "                       the four views of --methods;\n"
    "                       with --quick " QUICK_SCENES "; at most 16)\n"
    "  --out DIR            where the results go (default build/sweep)\n"
    "  --ref-dir DIR        cache of the path-traced references, kept between runs (default build/sweep/ref)\n"
    "  --baseline SCENE     the scene file whose settings are `high`, the point every variant changes one knob of\n"
    "                       (default " SW_DEFAULT_BASELINE ", the default scene)\n"
    "  --size WxH           size the error is measured at, references included (default 160x120; --quick 80x60)\n"
    "  --time-size WxH      size frames are timed at (default 640x480; --quick 160x120)\n"
    "  --spp N              path-tracer samples per pixel of the references, 1..1000000 (default 256; --quick 16)\n"
    "  --ref-threads N      threads the path tracer renders the references with, 1..256 (default 2); the images do\n"
    "                       not depend on it\n"
    "  --frames N           timed frames per configuration, their median taken (with --sun-step the mean),\n"
    "                       1..10000 (default 7; --quick 3)\n"
    "  --warmup N           untimed frames first, 0..10000 (default 1; --quick at most 1)\n"
    "  --threshold N        8-bit levels a tone-mapped channel may differ by before a pixel counts as visibly\n"
    "                       different, 0..255 (default 3)\n"
    "  --budgets M,L        time budgets of the medium and low presets as ratios to high's frame time,\n"
    "                       0 < L <= M <= 1 (default 0.5,0.25)\n"
    "  --quick              a short sweep: fewer views and knob values, smaller images, fewer frames\n"
    "  --sun-every-frame    time frames that redo the sun pass (the sun moved every frame), as `cumulo bench`\n"
    "  --sun-step DEG       timed frames turn the sun DEG degrees each, 0..10, the mean frame timed (the maps,\n"
    "                       closure, diffusion's solves in it); from 0.5 presets may take them (default 0.6;\n"
    "                       0, a still sun, with --methods or --sun-every-frame)\n"
    "";
/* the rest (C99 promises string literals of 4095 characters, not more) */
static const char HELP_MODES[] =
    "  --refs-only          render (or find) the references and stop\n"
    "  --methods            instead of the knobs: Kol's method (presets, segment counts) against the uniform ray\n"
    "                       march (quality.method = uniform, 8..128 steps x 2..8 toward the sun), timed interleaved,\n"
    "                       error on the cloud's pixels with contrast and SSIM; writes DIR/methods.md, methods.csv,\n"
    "                       methods.dat (default views " METHODS_SCENES ",\n"
    "                       baseline " METHODS_BASELINE ", or the first view's file with --scenes; time size\n"
    "                       320x240)\n"
    "  --fit-octaves        instead of the knobs: fit the octave model of multiple scattering (ms.octaves, ms.a, ms.b,\n"
    "                       ms.c) to the path tracer by coordinate descent on the cloud's pixels, error only; writes\n"
    "                       DIR/fit.md, fit.csv, fit.txt (default views the training scenes in scenes/fit/, 1024 spp)\n"
    "  --score DIR          instead of the knobs: score DIR/NAME.pfm of every view (linear radiance at --size,\n"
    "                       rendered elsewhere: another build's `cumulo render SCENE --size WxH -o DIR/NAME.pfm`,\n"
    "                       another renderer) against the references with the sweep's metrics; writes OUT/score.md\n"
    "  -h, --help           this help, then exit\n"
    "  -V, --version        the version, then exit\n"
    "\n"
    "Exit status: 0 done, 1 a failure while running (message on stderr), 2 a usage error.\n"
    "Run it from the source tree (scenes/, data/, scripts/sweep_plot.sh); `make sweep` runs it with the defaults.\n";

enum { O_SCENES = 256, O_OUT, O_REFDIR, O_BASELINE, O_SIZE, O_TSIZE, O_SPP, O_PTTHREADS, O_FRAMES, O_WARMUP,
       O_THRESHOLD, O_BUDGETS, O_QUICK, O_SUN, O_SUNSTEP, O_REFSONLY, O_METHODS, O_FIT, O_SCORE };

static const struct option LONG[] = {
    {"scenes", required_argument, NULL, O_SCENES},       {"out", required_argument, NULL, O_OUT},
    {"ref-dir", required_argument, NULL, O_REFDIR},      {"baseline", required_argument, NULL, O_BASELINE},
    {"size", required_argument, NULL, O_SIZE},           {"time-size", required_argument, NULL, O_TSIZE},
    {"spp", required_argument, NULL, O_SPP},             {"ref-threads", required_argument, NULL, O_PTTHREADS},
    {"frames", required_argument, NULL, O_FRAMES},       {"warmup", required_argument, NULL, O_WARMUP},
    {"threshold", required_argument, NULL, O_THRESHOLD}, {"budgets", required_argument, NULL, O_BUDGETS},
    {"quick", no_argument, NULL, O_QUICK},               {"sun-every-frame", no_argument, NULL, O_SUN},
    {"sun-step", required_argument, NULL, O_SUNSTEP},
    {"refs-only", no_argument, NULL, O_REFSONLY},        {"methods", no_argument, NULL, O_METHODS},
    {"fit-octaves", no_argument, NULL, O_FIT},          {"score", required_argument, NULL, O_SCORE},
    {"help", no_argument, NULL, 'h'},
    {"version", no_argument, NULL, 'V'},                 {NULL, 0, NULL, 0},
};

static int bad(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "cumulo-sweep: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    return 2;
}

static int parse_size(const char *v, int *w, int *h)
{
    unsigned long long wh[2];
    if (tool_parse_uints(v, 'x', 2, 1, 4096, wh))
        return -1;
    *w = (int)wh[0];
    *h = (int)wh[1];
    return 0;
}

static int is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* The views of a --scenes list. */
static int parse_views(sweep *sw, const char *scenes)
{
    char list[4096];
    if (strlen(scenes) >= sizeof list)
        return bad("--scenes: the list is longer than %d characters", (int)sizeof list - 1);
    snprintf(list, sizeof list, "%s", scenes);
    char *save = NULL;
    for (char *tok = strtok_r(list, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (sw->nviews == SW_MAX_SCENES)
            return bad("at most %d scenes", SW_MAX_SCENES);
        view *v = &sw->v[sw->nviews];
        size_t L = strlen(tok);
        if (strchr(tok, '/') || (L > 6 && strcmp(tok + L - 6, ".scene") == 0))
            snprintf(v->path, sizeof v->path, "%s", tok);
        else
            snprintf(v->path, sizeof v->path, "scenes/%s.scene", tok);
        const char *b = strrchr(v->path, '/');
        if (snprintf(v->name, sizeof v->name, "%s", b ? b + 1 : v->path) >= (int)sizeof v->name)
            return bad("scene name '%.40s...' is longer than %zu characters", b ? b + 1 : v->path, sizeof v->name - 1);
        char *dot = strstr(v->name, ".scene");
        if (dot)
            *dot = 0;
        if (!is_file(v->path))
            return bad("no scene file '%s'", v->path);
        for (int j = 0; j < sw->nviews; j++)
            if (strcmp(sw->v[j].name, v->name) == 0)
                return bad("scene '%s' given twice", v->name);
        sw->nviews++;
    }
    if (sw->nviews == 0)
        return bad("--scenes names no scene");
    return 0;
}

int sw_parse_options(sweep *sw, int argc, char **argv)
{
    memset(sw, 0, sizeof *sw);
    sw->ew = 160, sw->eh = 120, sw->tw = 640, sw->th = 480;
    sw->spp = 256, sw->frames = 7, sw->warmup = 1, sw->threshold = 3, sw->pt_threads = 2;
    sw->budget_med = 0.5, sw->budget_low = 0.25;
    sw->out = "build/sweep";
    sw->refdir = "build/sweep/ref";
    sw->plot = "scripts/sweep_plot.sh";
    sw->baseline = SW_DEFAULT_BASELINE;
    const char *scenes = NULL;
    int set_size = 0, set_tsize = 0, set_spp = 0, set_frames = 0, set_baseline = 0, set_sun_step = 0, c;
    opterr = 0;
    optind = 1;
    while ((c = getopt_long(argc, argv, ":hV", LONG, NULL)) != -1) {
        const char *v = optarg;
        switch (c) {
        case 'h':
            fputs(HELP, stdout);
            fputs(HELP_MODES, stdout);
            return -1;
        case 'V':
            printf("cumulo-sweep %s (%s)\n", CU_VERSION, CU_GIT_DESCRIBE);
            return -1;
        case ':':
            return bad("%s needs a value (see --help)", argv[optind - 1]);
        case '?':
            if (optopt > 0 && optopt < O_SCENES) /* a short option */
                return bad("unknown option '-%c' (see --help)", optopt);
            if (optopt == 0)
                return bad("unknown option '%s' (see --help)", argv[optind - 1]);
            return bad("'%s': the option takes no value (see --help)", argv[optind - 1]);
        case O_SCENES:
            if (!*v)
                return bad("--scenes expects a comma-separated list of scenes");
            scenes = v;
            break;
        case O_OUT:
            if (!*v)
                return bad("--out expects a directory");
            sw->out = v;
            break;
        case O_REFDIR:
            if (!*v)
                return bad("--ref-dir expects a directory");
            sw->refdir = v;
            break;
        case O_BASELINE:
            if (!is_file(v))
                return bad("--baseline: no scene file '%s'", v);
            sw->baseline = v;
            set_baseline = 1;
            break;
        case O_SIZE:
            if (parse_size(v, &sw->ew, &sw->eh))
                return bad("--size expects WxH with 1..4096, got '%s'", v);
            set_size = 1;
            break;
        case O_TSIZE:
            if (parse_size(v, &sw->tw, &sw->th))
                return bad("--time-size expects WxH with 1..4096, got '%s'", v);
            set_tsize = 1;
            break;
        case O_SPP:
            if (tool_parse_int(v, 1, 1000000, &sw->spp))
                return bad("--spp expects a count from 1 to 1000000, got '%s'", v);
            set_spp = 1;
            break;
        case O_PTTHREADS:
            if (tool_parse_int(v, 1, 256, &sw->pt_threads))
                return bad("--ref-threads expects a count from 1 to 256, got '%s'", v);
            break;
        case O_FRAMES:
            if (tool_parse_int(v, 1, 10000, &sw->frames))
                return bad("--frames expects a count from 1 to 10000, got '%s'", v);
            set_frames = 1;
            break;
        case O_WARMUP:
            if (tool_parse_int(v, 0, 10000, &sw->warmup))
                return bad("--warmup expects a count from 0 to 10000, got '%s'", v);
            break;
        case O_THRESHOLD:
            if (tool_parse_int(v, 0, 255, &sw->threshold))
                return bad("--threshold expects 8-bit levels from 0 to 255, got '%s'", v);
            break;
        case O_BUDGETS: {
            double m, l;
            char tail;
            if (sscanf(v, "%lf,%lf%c", &m, &l, &tail) != 2 || !(m > 0 && m <= 1) || !(l > 0 && l <= m))
                return bad("--budgets expects MEDIUM,LOW time ratios with 0 < LOW <= MEDIUM <= 1, got '%s'", v);
            sw->budget_med = m;
            sw->budget_low = l;
            break;
        }
        case O_QUICK:
            sw->quick = 1;
            break;
        case O_SUN:
            sw->sun_moving = 1;
            break;
        case O_SUNSTEP: {
            char *end;
            double d = strtod(v, &end);
            if (end == v || *end || !(d >= 0 && d <= 10))
                return bad("--sun-step expects degrees a frame from 0 to 10, got '%s'", v);
            sw->sun_step = d;
            set_sun_step = 1;
            break;
        }
        case O_REFSONLY:
            sw->refs_only = 1;
            break;
        case O_METHODS:
            sw->methods = 1;
            break;
        case O_FIT:
            sw->fit = 1;
            break;
        case O_SCORE:
            if (!*v)
                return bad("--score expects a directory of NAME.pfm images");
            sw->score = v;
            break;
        default:
            return bad("unknown option '%s' (see --help)", argv[optind - 1]);
        }
    }
    if (optind < argc)
        return bad("unexpected argument '%s' (see --help)", argv[optind]);
    if (sw->quick) {
        if (!scenes)
            scenes = QUICK_SCENES;
        if (!set_size)
            sw->ew = 80, sw->eh = 60;
        if (!set_tsize)
            sw->tw = 160, sw->th = 120;
        if (!set_spp)
            sw->spp = 16;
        if (!set_frames)
            sw->frames = 3;
        sw->warmup = sw->warmup < 1 ? sw->warmup : 1;
    }
    if (sw->sun_moving && set_sun_step)
        return bad("--sun-every-frame and --sun-step are two ways of moving the sun: give one");
    if (!set_sun_step && !sw->sun_moving && !sw->methods)
        sw->sun_step = DEFAULT_SUN_STEP;
    if (sw->methods + sw->fit + (sw->score != NULL) > 1)
        return bad("--methods, --fit-octaves and --score are different runs: give one");
    if (sw->fit) {
        if (!scenes)
            scenes = FIT_SCENES;
        if (!set_spp && !sw->quick)
            sw->spp = FIT_SPP;
    }
    int own_scenes = scenes != NULL;
    if (sw->methods) {
        if (!scenes)
            scenes = METHODS_SCENES;
        if (!set_baseline)
            sw->baseline = METHODS_BASELINE;
        if (!set_tsize && !sw->quick)
            sw->tw = 320, sw->th = 240;
    }
    int rc = parse_views(sw, scenes ? scenes : DEFAULT_SCENES);
    if (rc)
        return rc;
    /* --methods on views of one's own: `high` is the first view's settings, not the default views' (whose phase
     * function is Henyey-Greenstein: on views with the Mie table it would be compared with references it is not) */
    if (sw->methods && own_scenes && !set_baseline)
        sw->baseline = sw->v[0].path;
    return 0;
}
