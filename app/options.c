/* app/options.c: the options every cumulo subcommand shares, --version, and opening a scene on a display. */
#include "input_backend.h"
#include "session.h"
#include "version.h"
#include <errno.h>
#include <stdlib.h>
#include <string.h>

int cli_parse_counts(const char *v, char sep, int n, long lo, long hi, long *out)
{
    for (int i = 0; i < n; i++) {
        if (*v < '0' || *v > '9') /* strtol would take a sign and leading blanks */
            return -1;
        char *end;
        errno = 0;
        long x = strtol(v, &end, 10);
        if (errno == ERANGE || x < lo || x > hi || *end != (i == n - 1 ? '\0' : sep))
            return -1;
        out[i] = x;
        v = end + 1;
    }
    return 0;
}

int cli_common_getopt(cli_opts *o, int id, const char *v, const char *cmd)
{
    switch (id) {
    case 'v':
        o->verbose = 1;
        return 1;
    case CLI_OPT_SIZE: {
        long wh[2];
        if (cli_parse_counts(v, 'x', 2, 1, 16384, wh)) {
            fprintf(stderr, "%s: --size expects WxH with 1..16384, got '%s'\n", cmd, v);
            return -1;
        }
        o->width = (int)wh[0];
        o->height = (int)wh[1];
        return 1;
    }
    case CLI_OPT_BACKEND:
        o->backend = v;
        return 1;
    case CLI_OPT_DATA_DIR:
        o->data_dir = v;
        return 1;
    case CLI_OPT_TIME:
        if (o->nsets == CLI_MAX_SETS || strlen(v) > 40) {
            fprintf(stderr, "%s: --time expects seconds, got '%.40s'\n", cmd, v);
            return -1;
        }
        snprintf(o->time_set, sizeof o->time_set, "scene.time=%s", v);
        o->sets[o->nsets++] = o->time_set; /* the scene's own range check judges the value */
        return 1;
    case CLI_OPT_TARGET_FPS:
        if (o->nsets == CLI_MAX_SETS || strlen(v) > 40) {
            fprintf(stderr, "%s: --target-fps expects frames per second, got '%.40s'\n", cmd, v);
            return -1;
        }
        snprintf(o->fps_set, sizeof o->fps_set, "quality.target_fps=%s", v);
        o->sets[o->nsets++] = o->fps_set;
        return 1;
    case CLI_OPT_SET:
        if (o->nsets == CLI_MAX_SETS) {
            fprintf(stderr, "%s: at most %d --set options\n", cmd, CLI_MAX_SETS);
            return -1;
        }
        o->sets[o->nsets++] = v;
        return 1;
    default:
        return 0;
    }
}

void cli_print_version(FILE *f, const char *program)
{
    fprintf(f, "%s %s (%s), libcumulo %s\n", program, CU_VERSION, CU_GIT_DESCRIBE, cu_version());
    fprintf(f, "display back ends: headless");
    for (int i = 0; cu_display_backends[i]; i++)
        fprintf(f, " %s", cu_display_backends[i]->name);
    fprintf(f, "\ninputs:");
    for (int i = 0; cu_input_backends[i]; i++)
        fprintf(f, " %s", cu_input_backends[i]->name);
    fprintf(f, "\n");
    fprintf(f, "data: %s\n", cu_default_data_dir());
}

static int fail_open(cli_session *s, int rc, const char *msg)
{
    (void)s;
    fprintf(stderr, "cumulo: %s\n", msg);
    return rc;
}

int cli_session_open(cli_session *s, const cli_opts *o)
{
    memset(s, 0, sizeof *s);
    s->verbose = o->verbose;
    cu_error e;
    if (cu_scene_load(&s->scene, o->scene_path, &e))
        return fail_open(s, 1, e.msg);
    for (int i = 0; i < o->nsets; i++)
        if (cu_scene_set(s->scene, o->sets[i], &e))
            return fail_open(s, 2, e.msg);
    cu_scene_output_size(s->scene, &s->width, &s->height);
    if (o->width) {
        s->width = o->width;
        s->height = o->height;
    }
    const cu_display_backend *be = cu_display_find(o->backend);
    if (!be) {
        char msg[512];
        int n = snprintf(msg, sizeof msg, "unknown back end '%s'; built:", o->backend);
        for (int i = 0; cu_display_backends[i] && n > 0 && n < (int)sizeof msg; i++)
            n += snprintf(msg + n, sizeof msg - (size_t)n, " %s", cu_display_backends[i]->name);
        return fail_open(s, 2, msg);
    }
    cu_display_opts dopt = {0};
    dopt.width = s->width;
    dopt.height = s->height;
    dopt.float_target = o->linear;
    char err[600];
    if (cli_session_attach(s, be, &dopt, cli_data_dir(o), o->verbose, err, sizeof err))
        return fail_open(s, 1, err);
    if (cu_renderer_set_scene(s->r, s->scene, &e))
        return fail_open(s, 1, e.msg);
    return 0;
}

