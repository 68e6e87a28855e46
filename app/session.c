/* src/cli/session.c: shared set-up of the cumulo subcommands (see session.h). */
#include "session.h"
#include <GLES3/gl3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#ifndef CU_INSTALL_DATA_DIR
#define CU_INSTALL_DATA_DIR "/usr/local/share/cumulo/data"
#endif

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

int cli_common_option(cli_opts *o, int argc, char **argv, int *i)
{
    const char *a = argv[*i];
    if (strcmp(a, "-v") == 0 || strcmp(a, "--verbose") == 0) {
        o->verbose = 1;
        return 1;
    }
    if (strcmp(a, "--size") != 0 && strcmp(a, "--backend") != 0 && strcmp(a, "--set") != 0 &&
        strcmp(a, "--platform") != 0)
        return 0;
    if (*i + 1 >= argc) {
        fprintf(stderr, "cumulo: %s needs a value\n", a);
        return -1;
    }
    const char *v = argv[++*i];
    if (strcmp(a, "--size") == 0) {
        int w, h;
        char tail;
        if (sscanf(v, "%dx%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384) {
            fprintf(stderr, "cumulo: --size expects WxH with 1..16384, got '%s'\n", v);
            return -1;
        }
        o->width = w;
        o->height = h;
    } else if (strcmp(a, "--backend") == 0 || strcmp(a, "--platform") == 0) {
        o->backend = v;
    } else {
        if (o->nsets == CLI_MAX_SETS) {
            fprintf(stderr, "cumulo: at most %d --set options\n", CLI_MAX_SETS);
            return -1;
        }
        o->sets[o->nsets++] = v;
    }
    return 1;
}

int cli_session_open(cli_session *s, const cli_opts *o)
{
    static int verbose; /* the log callback's user data must outlive the call */
    memset(s, 0, sizeof *s);
    verbose = o->verbose;
    cu_error e;
    if (cu_scene_load(&s->scene, o->scene_path, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return 1;
    }
    for (int i = 0; i < o->nsets; i++)
        if (cu_scene_set(s->scene, o->sets[i], &e)) {
            fprintf(stderr, "%s\n", e.msg);
            return 1;
        }
    cu_scene_output_size(s->scene, &s->width, &s->height);
    if (o->width) {
        s->width = o->width;
        s->height = o->height;
    }
    s->linear = o->linear;
    s->be = cu_display_find(o->backend);
    if (!s->be) {
        fprintf(stderr, "cumulo: unknown back end '%s'; built:", o->backend);
        for (int i = 0; cu_display_backends[i]; i++)
            fprintf(stderr, " %s", cu_display_backends[i]->name);
        fprintf(stderr, "\n");
        return 1;
    }
    cu_display_opts dopt = {0};
    dopt.width = s->width;
    dopt.height = s->height;
    dopt.float_target = o->linear;
    char err[512];
    if (s->be->open(&s->disp, &dopt, err, sizeof err)) {
        fprintf(stderr, "cumulo: %s\n", err);
        return 1;
    }
    int w, h;
    s->be->frame(s->disp, &s->fbo, &w, &h);
    s->width = w;
    s->height = h;
    cu_desc d = {0};
    d.get_proc_address = getproc;
    d.get_proc_user = s;
    d.log = log_to_stderr;
    d.log_user = &verbose;
    /* Tables: $CUMULO_DATA_DIR, else ./data (a source tree), else where `make install` put them. */
    const char *dd = getenv("CUMULO_DATA_DIR");
    struct stat sb;
    if (!dd)
        dd = stat("data/mie_cloud.tbl", &sb) == 0 ? "data" : CU_INSTALL_DATA_DIR;
    d.data_dir = dd;
    if (cu_renderer_create(&s->r, &d, &e) || cu_renderer_set_scene(s->r, s->scene, &e)) {
        fprintf(stderr, "cumulo: %s\n", e.msg);
        return 1;
    }
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
    cu_renderer_destroy(s->r);
    if (s->disp)
        s->be->close(s->disp);
    cu_scene_free(s->scene);
    memset(s, 0, sizeof *s);
}
