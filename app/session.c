/* app/session.c: shared set-up of the cumulo subcommands (see session.h). */
#include "session.h"
#include "config.h"
#include "version.h"
#include <GLES3/gl3.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static void log_to_stderr(void *user, cu_log_level level, const char *msg)
{
    int verbose = *(const int *)user;
    static const char *names[] = {"error", "warning", "info", "debug"};
    if (level <= CU_LOG_WARN || verbose)
        fprintf(stderr, "cumulo: %s: %s\n", names[level], msg);
}

static void *getproc(void *user, const char *name)
{
    cli_session *s = user;
    return s->be->get_proc_address(s->disp, name);
}

int cli_common_getopt(cli_opts *o, int id, const char *v, const char *cmd)
{
    switch (id) {
    case 'v':
        o->verbose = 1;
        return 1;
    case CLI_OPT_SIZE: {
        int w, h;
        char tail;
        if (sscanf(v, "%dx%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384 ||
            strspn(v, "0123456789x") != strlen(v) || strlen(v) > 11) {
            fprintf(stderr, "%s: --size expects WxH with 1..16384, got '%s'\n", cmd, v);
            return -1;
        }
        o->width = w;
        o->height = h;
        return 1;
    }
    case CLI_OPT_BACKEND:
        o->backend = v;
        return 1;
    case CLI_OPT_DATA_DIR:
        o->data_dir = v;
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

int cli_common_option(cli_opts *o, int argc, char **argv, int *i)
{
    static const struct { const char *name; int id; } opts[] = {
        {"--size", CLI_OPT_SIZE}, {"--backend", CLI_OPT_BACKEND}, {"--platform", CLI_OPT_BACKEND},
        {"--set", CLI_OPT_SET},   {"--data-dir", CLI_OPT_DATA_DIR},
    };
    const char *a = argv[*i];
    if (strcmp(a, "-v") == 0 || strcmp(a, "--verbose") == 0)
        return cli_common_getopt(o, 'v', NULL, "cumulo");
    for (size_t k = 0; k < sizeof opts / sizeof opts[0]; k++) {
        if (strcmp(a, opts[k].name) != 0)
            continue;
        if (*i + 1 >= argc) {
            fprintf(stderr, "cumulo: %s needs a value\n", a);
            return -1;
        }
        return cli_common_getopt(o, opts[k].id, argv[++*i], "cumulo");
    }
    return 0;
}

void cli_print_version(FILE *f, const char *program)
{
    fprintf(f, "%s %s (%s), libcumulo %s\n", program, CU_VERSION, CU_GIT_DESCRIBE, cu_version());
    fprintf(f, "display back ends: headless");
    for (int i = 0; cu_display_backends[i]; i++)
        fprintf(f, " %s", cu_display_backends[i]->name);
    fprintf(f, "\ninputs: stdin evdev%s\n", CU_HAVE_GPIOD ? " gpio" : "");
    fprintf(f, "data: %s\n", cu_default_data_dir());
}

const char *cli_data_dir(const cli_opts *o)
{
    static char exe_data[PATH_MAX];
    if (o->data_dir)
        return o->data_dir;
    const char *env = getenv("CUMULO_DATA_DIR");
    if (env && *env)
        return env;
    /* Run from a build tree (build/cumulo): the tables are the source tree's, not an older installed copy. */
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = 0;
            struct stat sb;
            char probe[PATH_MAX + 32];
            snprintf(probe, sizeof probe, "%s/../data/mie_cloud.tbl", exe);
            if (stat(probe, &sb) == 0 && strlen(exe) + 8 < sizeof exe_data) {
                snprintf(exe_data, sizeof exe_data, "%s/../data", exe);
                return exe_data;
            }
        }
    }
    return NULL;
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
    s->linear = o->linear;
    s->be = cu_display_find(o->backend);
    if (!s->be) {
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
    char err[512];
    if (s->be->open(&s->disp, &dopt, err, sizeof err)) {
        s->disp = NULL;
        return fail_open(s, 1, err);
    }
    int w, h;
    s->be->frame(s->disp, &s->fbo, &w, &h);
    s->width = w;
    s->height = h;
    cu_desc d = {0};
    d.get_proc_address = getproc;
    d.get_proc_user = s;
    d.log = log_to_stderr;
    d.log_user = &s->verbose;
    d.data_dir = cli_data_dir(o);
    if (cu_renderer_create(&s->r, &d, &e) || cu_renderer_set_scene(s->r, s->scene, &e))
        return fail_open(s, 1, e.msg);
    return 0;
}

int cli_session_render(cli_session *s)
{
    cu_error e;
    cu_frame f = {s->fbo, s->width, s->height, s->linear};
    if (cu_render(s->r, &f, &e)) {
        fprintf(stderr, "cumulo: %s\n", e.msg);
        return 1;
    }
    char err[256];
    if (s->be->present(s->disp, err, sizeof err)) {
        fprintf(stderr, "cumulo: %s\n", err);
        return 1;
    }
    return 0;
}

typedef void (*read_pixels_fn)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *);
typedef void (*bind_fb_fn)(GLenum, GLuint);

static int read_pixels(cli_session *s, GLenum type, void *buf)
{
    void *rp = s->be->get_proc_address(s->disp, "glReadPixels");
    void *bf = s->be->get_proc_address(s->disp, "glBindFramebuffer");
    if (!rp || !bf) {
        fprintf(stderr, "cumulo: glReadPixels unavailable\n");
        return 1;
    }
    read_pixels_fn read;
    bind_fb_fn bind;
    memcpy(&read, &rp, sizeof rp);
    memcpy(&bind, &bf, sizeof bf);
    bind(GL_FRAMEBUFFER, s->fbo);
    read(0, 0, s->width, s->height, GL_RGBA, type, buf);
    return 0;
}

int cli_session_read_rgba8(cli_session *s, uint8_t *out)
{
    size_t row = (size_t)s->width * 4;
    uint8_t *tmp = malloc(row * (size_t)s->height);
    if (!tmp || read_pixels(s, GL_UNSIGNED_BYTE, tmp)) {
        free(tmp);
        return 1;
    }
    for (int y = 0; y < s->height; y++) /* GL's first row is the bottom one */
        memcpy(out + (size_t)y * row, tmp + (size_t)(s->height - 1 - y) * row, row);
    free(tmp);
    return 0;
}

int cli_session_read_rgbf(cli_session *s, float *out)
{
    size_t n = (size_t)s->width * s->height;
    float *tmp = malloc(sizeof(float) * 4 * n);
    if (!tmp || read_pixels(s, GL_FLOAT, tmp)) {
        free(tmp);
        return 1;
    }
    for (int y = 0; y < s->height; y++)
        for (int x = 0; x < s->width; x++)
            for (int c = 0; c < 3; c++)
                out[((size_t)y * s->width + x) * 3 + c] = tmp[((size_t)(s->height - 1 - y) * s->width + x) * 4 + c];
    free(tmp);
    return 0;
}

void cli_session_close(cli_session *s)
{
    if (s->r)
        cu_renderer_destroy(s->r);
    if (s->disp)
        s->be->close(s->disp);
    cu_scene_free(s->scene);
    memset(s, 0, sizeof *s);
}
