/* src/gl.c: GL entry-point loading and shader compilation with file-named errors (see gl.h). */
#include "gl.h"
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Default loader: the GL functions the process already links (a plain GLES program). */
static void *dlsym_loader(void *user, const char *name)
{
    (void)user;
    void *self = dlopen(NULL, RTLD_LAZY);
    void *p = self ? dlsym(self, name) : NULL;
    if (self)
        dlclose(self);
    return p;
}

int cu_gl_load(cu_gl *gl, cu_get_proc_fn get, void *user, cu_error *err)
{
    if (!get)
        get = dlsym_loader;
    memset(gl, 0, sizeof *gl);
    void *p;
#define CU_GL_LOAD(name, NAME)                                                                   \
    p = get(user, "gl" #name);                                                                   \
    if (!p) {                                                                                    \
        snprintf(err->msg, sizeof err->msg, "GL entry point gl%s is missing (is a GLES 3 context current?)", #name); \
        return 1;                                                                                \
    }                                                                                            \
    memcpy(&gl->name, &p, sizeof p);
    CU_GL_FUNCS(CU_GL_LOAD)
#undef CU_GL_LOAD
    return 0;
}

int cu_gl_has_extension(const cu_gl *gl, const char *name)
{
    GLint n = 0;
    gl->GetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++) {
        const char *e = (const char *)gl->GetStringi(GL_EXTENSIONS, (GLuint)i);
        if (e && strcmp(e, name) == 0)
            return 1;
    }
    return 0;
}

static GLuint compile(const cu_gl *gl, GLenum type, const cu_shader_src *src, const char *defines, cu_error *err)
{
    /* Line 0 is the #version line; the scene's #defines go right after it, then a #line directive so the
     * driver's messages keep the file's own line numbers. */
    int n = src->nlines + 2;
    const char **parts = malloc(sizeof *parts * (size_t)n);
    if (!parts) {
        snprintf(err->msg, sizeof err->msg, "shaders_gles/%s: out of memory", src->name);
        return 0;
    }
    parts[0] = src->lines[0];
    parts[1] = defines ? defines : "";
    parts[2] = "#line 2\n";
    for (int i = 1; i < src->nlines; i++)
        parts[i + 2] = src->lines[i];
    GLuint sh = gl->CreateShader(type);
    gl->ShaderSource(sh, n, parts, NULL);
    free(parts);
    gl->CompileShader(sh);
    GLint ok = 0;
    gl->GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[400] = "";
        gl->GetShaderInfoLog(sh, sizeof log, NULL, log);
        for (char *c = log; *c; c++)
            if (*c == '\n') *c = ' ';
        snprintf(err->msg, sizeof err->msg, "shaders_gles/%s: compile failed: %s", src->name, log);
        gl->DeleteShader(sh);
        return 0;
    }
    return sh;
}

GLuint cu_gl_program(const cu_gl *gl, const char *vs_name, const char *fs_name, const char *defines, cu_error *err)
{
    const cu_shader_src *vs = cu_shader_find(vs_name), *fs = cu_shader_find(fs_name);
    if (!vs || !fs) {
        snprintf(err->msg, sizeof err->msg, "shaders_gles/%s: not embedded in this build", vs ? fs_name : vs_name);
        return 0;
    }
    GLuint v = compile(gl, GL_VERTEX_SHADER, vs, defines, err);
    if (!v)
        return 0;
    GLuint f = compile(gl, GL_FRAGMENT_SHADER, fs, defines, err);
    if (!f) {
        gl->DeleteShader(v);
        return 0;
    }
    GLuint p = gl->CreateProgram();
    gl->AttachShader(p, v);
    gl->AttachShader(p, f);
    gl->LinkProgram(p);
    gl->DeleteShader(v);
    gl->DeleteShader(f);
    GLint ok = 0;
    gl->GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[400] = "";
        gl->GetProgramInfoLog(p, sizeof log, NULL, log);
        for (char *c = log; *c; c++)
            if (*c == '\n') *c = ' ';
        snprintf(err->msg, sizeof err->msg, "shaders_gles/%s + %s: link failed: %s", vs_name, fs_name, log);
        gl->DeleteProgram(p);
        return 0;
    }
    return p;
}
