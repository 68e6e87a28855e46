/* src/cli/session.h: what every cumulo subcommand shares: parse the common options, open a display back end,
 * load the scene with --set overrides, create the renderer, read pixels back. */
#ifndef CU_CLI_SESSION_H
#define CU_CLI_SESSION_H
#include "display.h"
#include "cumulo.h"
#include <stdint.h>

#define CLI_MAX_SETS 64

typedef struct cli_opts {
    const char *scene_path;
    const char *backend;      /* NULL = egl */
    int width, height;        /* 0 = scene's */
    int linear;               /* render linear radiance into a float target */
    const char *sets[CLI_MAX_SETS];
    int nsets;
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
} cli_session;

/* Consumes a common option at argv[*i] (--size, --backend, --set, -v); returns 1 if it was one, 0 if not, -1 on a
 * bad value (message printed). */
int cli_common_option(cli_opts *o, int argc, char **argv, int *i);
/* Opens everything; prints a one-line error and returns non-zero on failure. */
int cli_session_open(cli_session *s, const cli_opts *o);
int cli_session_render(cli_session *s);
/* Reads the frame back (top row first): RGBA8 for tone-mapped, RGB float for linear. */
int cli_session_read_rgba8(cli_session *s, uint8_t *out);
int cli_session_read_rgbf(cli_session *s, float *out);
void cli_session_close(cli_session *s);
#endif
