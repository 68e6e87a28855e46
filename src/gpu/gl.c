/* src/gpu/gl.c: GL entry-point loading and shader compilation with file-named errors (see gl.h). */
#include "gl.h"
#include "error.h"
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
#define CU_GL_LOAD(name, NAME)                                                                        \
    p = get(user, "gl" #name);                                                                        \
    if (!p)                                                                                           \
        return cu_fail(err, "GL entry point gl%s is missing (is a GLES 3 context current?)", #name); \
    memcpy(&gl->name, &p, sizeof p);
    CU_GL_FUNCS(CU_GL_LOAD)
#undef CU_GL_LOAD
    return 0;
}

void *cu_gl_optional(cu_get_proc_fn get, void *user, const char *name)
{
    if (get)
        return get(user, name);
    void *p = dlsym_loader(NULL, name);
    if (p)
        return p;
    /* glvnd's libGLESv2 exports the core functions only: an extension's come from EGL, when the process has it */
    void *(*egl_get)(const char *);
    void *e = dlsym_loader(NULL, "eglGetProcAddress");
    if (!e)
        return NULL;
    memcpy(&egl_get, &e, sizeof e);
    return egl_get(name);
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

/* Builds the source as an array of lines: the #version line, the scene's #defines, then the file with each
 * `#include "x.glsl"` replaced by that embedded file. #line directives keep the driver's messages pointing at the
 * right file (source string 0 = the main file, 1.. = its includes in order) and line. */
static GLuint compile(const cu_gl *gl, GLenum type, const cu_shader_src *src, const char *defines, cu_error *err)
{
    int cap = src->nlines + 8;
    for (int i = 1; i < src->nlines; i++)
        if (strncmp(src->lines[i], "#include \"", 10) == 0) {
            char name[64];
            if (sscanf(src->lines[i] + 10, "%63[^\"]", name) == 1 && cu_shader_find(name))
                cap += cu_shader_find(name)->nlines + 2;
        }
    const char **parts = malloc(sizeof *parts * (size_t)cap);
    char(*dirs)[40] = malloc(sizeof *dirs * (size_t)cap);
    char names[256];
    snprintf(names, sizeof names, "0 %s", src->name);
    if (!parts || !dirs) {
        free(parts);
        free(dirs);
        cu_fail(err, "shaders_gles/%s: out of memory", src->name);
        return 0;
    }
    int n = 0, nd = 0, nfile = 0;
    parts[n++] = src->lines[0];
    parts[n++] = defines ? defines : "";
    parts[n++] = "#line 2 0\n";
    for (int i = 1; i < src->nlines; i++) {
        if (strncmp(src->lines[i], "#include \"", 10) != 0) {
            parts[n++] = src->lines[i];
            continue;
        }
        char name[64] = "";
        const cu_shader_src *inc = NULL;
        if (sscanf(src->lines[i] + 10, "%63[^\"]", name) == 1)
            inc = cu_shader_find(name);
        if (!inc) {
            cu_fail(err, "shaders_gles/%s:%d: cannot include '%s'", src->name, i + 1, name);
            free(parts);
            free(dirs);
            return 0;
        }
        nfile++;
        size_t l = strlen(names);
        snprintf(names + l, sizeof names - l, ", %d %s", nfile, inc->name);
        snprintf(dirs[nd], sizeof dirs[nd], "#line 1 %d\n", nfile);
        parts[n++] = dirs[nd++];
        for (int k = 0; k < inc->nlines; k++)
            parts[n++] = inc->lines[k];
        snprintf(dirs[nd], sizeof dirs[nd], "#line %d 0\n", i + 2);
        parts[n++] = dirs[nd++];
    }
    GLuint sh = gl->CreateShader(type);
    gl->ShaderSource(sh, n, parts, NULL);
    free(parts);
    free(dirs);
    gl->CompileShader(sh);
    GLint ok = 0;
    gl->GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[300] = "";
        gl->GetShaderInfoLog(sh, sizeof log, NULL, log);
        for (char *c = log; *c; c++)
            if (*c == '\n') *c = ' ';
        cu_fail(err, "shaders_gles/%s (sources %s): compile failed: %s", src->name, names, log);
        gl->DeleteShader(sh);
        return 0;
    }
    return sh;
}

GLuint cu_gl_program(const cu_gl *gl, const char *vs_name, const char *fs_name, const char *defines, cu_error *err)
{
    const cu_shader_src *vs = cu_shader_find(vs_name), *fs = cu_shader_find(fs_name);
    if (!vs || !fs) {
        cu_fail(err, "shaders_gles/%s: not embedded in this build", vs ? fs_name : vs_name);
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
        cu_fail(err, "shaders_gles/%s + %s: link failed: %s", vs_name, fs_name, log);
        gl->DeleteProgram(p);
        return 0;
    }
    return p;
}
