/* app/session.c: a display back end with a renderer on its context, frames, pixels read back (see session.h). */
#include "session.h"
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

const char *cli_data_dir(const cli_opts *o)
{
    static char exe_data[PATH_MAX + 16];
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
            if (stat(probe, &sb) == 0) {
                snprintf(exe_data, sizeof exe_data, "%s/../data", exe);
                return exe_data;
            }
        }
    }
    return NULL;
}

int cli_session_attach(cli_session *s, const cu_display_backend *be, const cu_display_opts *dopt,
                       const char *data_dir, int verbose, char *err, size_t errlen)
{
    cu_scene *scene = s->scene;
    memset(s, 0, sizeof *s);
    s->scene = scene;
    s->be = be;
    s->linear = dopt->float_target;
    s->verbose = verbose;
    if (be->open(&s->disp, dopt, err, errlen)) {
        s->disp = NULL;
        return 1;
    }
    be->frame(s->disp, &s->fbo, &s->width, &s->height);
    cu_desc d = {0};
    d.get_proc_address = getproc;
    d.get_proc_user = s;
    d.log = log_to_stderr;
    d.log_user = &s->verbose;
    d.data_dir = data_dir;
    cu_error e;
    if (cu_renderer_create(&s->r, &d, &e)) {
        snprintf(err, errlen, "%s", e.msg);
        return 1;
    }
    return 0;
}

int cli_session_render(cli_session *s)
{
    return cli_session_render_view(s, NULL, NULL);
}

int cli_session_render_view(cli_session *s, const float *view, const float *projection)
{
    cu_error e;
    cu_frame f = {.fbo = s->fbo, .width = s->width, .height = s->height, .linear = s->linear, .view = view,
                  .projection = projection};
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
