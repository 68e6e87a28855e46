/* app/session.h: what every cumulo subcommand (and the sweep) shares: the common options, the data folder, opening a
 * display back end with a scene and a renderer, rendering, reading pixels back. */
#ifndef CU_APP_SESSION_H
#define CU_APP_SESSION_H
#include "cumulo.h"
#include "display.h"
#include <getopt.h>
#include <stdint.h>
#include <stdio.h>

#define CLI_MAX_SETS 64

typedef struct cli_opts {
    const char *scene_path;
    const char *backend;      /* NULL = egl (headless) */
    int width, height;        /* 0 = scene's */
    int linear;               /* render linear radiance into a float target */
    const char *sets[CLI_MAX_SETS];
    int nsets;
    const char *data_dir;     /* --data-dir; NULL = cli_data_dir()'s search */
    char time_set[64];        /* --time T as the --set it stands for */
    char fps_set[64];         /* --target-fps F likewise */
    int verbose;
} cli_opts;

typedef struct cli_session {
    const cu_display_backend *be;
    cu_display *disp;
    cu_scene *scene;
    cu_renderer *r;
    unsigned fbo;
    int width, height;
    int linear;
    int verbose;
} cli_session;

/* getopt_long entries of the common options, for a subcommand's option table; their ids are CLI_OPT_*. */
enum { CLI_OPT_SIZE = 0x100, CLI_OPT_BACKEND, CLI_OPT_SET, CLI_OPT_DATA_DIR, CLI_OPT_HELP, CLI_OPT_VERSION,
       CLI_OPT_TIME, CLI_OPT_TARGET_FPS };
#define CLI_COMMON_LONGOPTS                                                                                      \
    {"size", required_argument, NULL, CLI_OPT_SIZE}, {"backend", required_argument, NULL, CLI_OPT_BACKEND},    \
    {"platform", required_argument, NULL, CLI_OPT_BACKEND}, {"set", required_argument, NULL, CLI_OPT_SET},    \
    {"data-dir", required_argument, NULL, CLI_OPT_DATA_DIR}, {"verbose", no_argument, NULL, 'v'},             \
    {"time", required_argument, NULL, CLI_OPT_TIME}, {"target-fps", required_argument, NULL, CLI_OPT_TARGET_FPS}, \
    {"help", no_argument, NULL, 'h'}, {"version", no_argument, NULL, CLI_OPT_VERSION}
/* The common options' lines for a subcommand's --help. */
#define CLI_COMMON_HELP                                                                                          \
    "  --size WxH             output size in pixels, 1..16384 (default: the scene's [output] size)\n"           \
    "  --backend NAME         display back end: egl (= headless), osmesa, ... (cumulo --version lists them)\n"   \
    "  --set SECTION.KEY=V    override one scene value (repeatable; ellipsoid.N.key for the N-th ellipsoid)\n"   \
    "  --time T               the scene time in seconds (= --set scene.time=T): wind, life cycles, time_utc\n"    \
    "  --target-fps F         a frame budget (= --set quality.target_fps=F): coarser clouds while frames are slow\n" \
    "  --data-dir DIR         the tables (mie_cloud.tbl, ...); default $CUMULO_DATA_DIR, the build tree's\n"      \
    "                         data/ when run from it, else the installed copy\n"                                 \
    "  -v, --verbose          log the renderer's choices (GL strings, fallbacks)\n"                            \
    "  -h, --help             this help; --version: version and back ends\n"

/* Reads v as exactly n decimal counts separated by sep ("64x48", "30"), each in [lo, hi] (lo >= 0), into out: 0, or -1
 * for anything else. Digits only; an overflow of long (ERANGE) is an error, not a clamped or wrapped value. */
int cli_parse_counts(const char *v, char sep, int n, long lo, long hi, long *out);
/* Handles a common option returned by getopt_long (id, optarg): 1 = handled, 0 = not common, -1 = bad value (one
 * line printed, exit 2). `cmd` names the subcommand in messages. */
int cli_common_getopt(cli_opts *o, int id, const char *arg, const char *cmd);
/* Prints "cumulo VERSION (git describe)" and the display back ends and inputs of this build. */
void cli_print_version(FILE *f, const char *program);
/* The tables' folder: --data-dir, else $CUMULO_DATA_DIR, else ../data beside the executable when it holds the
 * tables (a build tree), else NULL (the library's installed default). */
const char *cli_data_dir(const cli_opts *o);

/* Opens back end `be` with `dopt` (size, float target, drm mode and device, ...) and a renderer on its context
 * reading the tables from data_dir (NULL = the library's default). Keeps s->scene; prints nothing: returns 1 with a
 * message in err. Every subcommand, the sweep and the image tests open a display through this. */
int cli_session_attach(cli_session *s, const cu_display_backend *be, const cu_display_opts *dopt,
                       const char *data_dir, int verbose, char *err, size_t errlen);
/* Loads o->scene_path with its --set overrides, finds the back end and attaches; prints one line and returns 2 for a usage error (unknown back end, bad --set), 1 for a runtime
 * failure, 0 on success. cli_session_close is safe after a failed open. */
int cli_session_open(cli_session *s, const cli_opts *o);
int cli_session_render(cli_session *s);
/* The same with the host-style camera matrices of cu_frame (both NULL: the scene's [camera]). */
int cli_session_render_view(cli_session *s, const float *view, const float *projection);
/* Reads the frame back (top row first): RGBA8 for tone-mapped, RGB float for linear. */
int cli_session_read_rgba8(cli_session *s, uint8_t *out);
int cli_session_read_rgbf(cli_session *s, float *out);
void cli_session_close(cli_session *s);
#endif
