/* platform/display/headless_fbo.c: offscreen colour target for the headless back ends (see headless_fbo.h). */
#include "headless_fbo.h"
#include <GLES3/gl3.h>
#include <stdio.h>
#include <string.h>

#define LOAD(T, name) T name; { void *p_ = getproc(#name); if (!p_) { snprintf(err, errlen, "missing %s", #name); return 1; } memcpy(&name, &p_, sizeof p_); }

int cu_headless_fbo_create(cu_headless_fbo *f, cu_headless_getproc getproc, int w, int h, int float_target,
                           char *err, size_t errlen)
{
    LOAD(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)
    LOAD(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)
    LOAD(PFNGLGENTEXTURESPROC, glGenTextures)
    LOAD(PFNGLBINDTEXTUREPROC, glBindTexture)
    LOAD(PFNGLTEXIMAGE2DPROC, glTexImage2D)
    LOAD(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D)
    LOAD(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)
    memset(f, 0, sizeof *f);
    f->width = w;
    f->height = h;
    f->float_target = float_target;
    glGenTextures(1, &f->color);
    glBindTexture(GL_TEXTURE_2D, f->color);
    glTexImage2D(GL_TEXTURE_2D, 0, float_target ? GL_RGBA32F : GL_RGBA8, w, h, 0, GL_RGBA,
                 float_target ? GL_FLOAT : GL_UNSIGNED_BYTE, NULL);
    glGenFramebuffers(1, &f->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, f->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, f->color, 0);
    GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(err, errlen, "offscreen %s framebuffer %dx%d incomplete (0x%x)%s", float_target ? "RGBA32F" : "RGBA8",
                 w, h, st, float_target ? ": the context cannot render to float targets" : "");
        return 1;
    }
    return 0;
}

void cu_headless_fbo_destroy(cu_headless_fbo *f, cu_headless_getproc getproc)
{
    PFNGLDELETEFRAMEBUFFERSPROC del_fb;
    PFNGLDELETETEXTURESPROC del_tex;
    void *a = getproc("glDeleteFramebuffers"), *b = getproc("glDeleteTextures");
    if (!a || !b)
        return;
    memcpy(&del_fb, &a, sizeof a);
    memcpy(&del_tex, &b, sizeof b);
    if (f->fbo) del_fb(1, &f->fbo);
    if (f->color) del_tex(1, &f->color);
    f->fbo = f->color = 0;
}
