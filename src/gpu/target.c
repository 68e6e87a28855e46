/* src/gpu/target.c: render targets (see target.h). */
#include "target.h"
#include "error.h"
#include <string.h>

static GLenum pixel_type(GLenum format)
{
    switch (format) {
    case GL_RGBA32F:
    case GL_DEPTH_COMPONENT32F:
        return GL_FLOAT;
    case GL_RGBA16F:
        return GL_HALF_FLOAT;
    default:
        return GL_UNSIGNED_BYTE;
    }
}

static const char *format_name(GLenum format)
{
    switch (format) {
    case GL_RGBA32F: return "RGBA32F";
    case GL_RGBA16F: return "RGBA16F";
    case GL_RGBA8: return "RGBA8";
    case GL_DEPTH_COMPONENT32F: return "DEPTH_COMPONENT32F";
    default: return "?";
    }
}

static void alloc_texture(const cu_gl *gl, const cu_target_desc *d, int depth)
{
    GLenum fmt = depth ? GL_DEPTH_COMPONENT : GL_RGBA, type = pixel_type(d->format);
    if (d->mipmaps) {
        int level = 0;
        for (int w = d->width, h = d->height;; level++) {
            gl->TexImage2D(GL_TEXTURE_2D, level, (GLint)d->format, w, h, 0, fmt, type, NULL);
            if (w == 1 && h == 1)
                break;
            w = w > 1 ? w / 2 : 1;
            h = h > 1 ? h / 2 : 1;
        }
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, level);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        return;
    }
    gl->TexImage2D(GL_TEXTURE_2D, 0, (GLint)d->format, d->width, d->height, 0, fmt, type, NULL);
    /* NEAREST: the shaders read texels (texelFetch); depth textures are not filterable in GLES 3.0 without
     * comparison anyway. */
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (depth) {
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    }
}

/* Over a limit, TexImage2D and RenderbufferStorage only raise GL_INVALID_VALUE and the framebuffer reads as
 * incomplete, which does not say why: the size is checked against the limits first, and the message names them. */
static int check_limits(const cu_gl *gl, const cu_target_desc *d, cu_error *err)
{
    GLint tex = 0, rb = 0, vp[2] = {0, 0};
    gl->GetIntegerv(GL_MAX_TEXTURE_SIZE, &tex);
    gl->GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &rb);
    gl->GetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
    int over = d->width > tex || d->height > tex || d->width > vp[0] || d->height > vp[1] ||
               (d->depth_stencil && (d->width > rb || d->height > rb));
    if (over)
        return cu_fail(err, "%s: framebuffer %dx%d exceeds this GPU's limit (GL_MAX_TEXTURE_SIZE %d, "
                       "GL_MAX_RENDERBUFFER_SIZE %d, GL_MAX_VIEWPORT_DIMS %dx%d)", d->name, d->width, d->height,
                       (int)tex, (int)rb, (int)vp[0], (int)vp[1]);
    return 0;
}

int cu_target_create(cu_target *t, const cu_gl *gl, const cu_target_desc *d, cu_error *err)
{
    memset(t, 0, sizeof *t);
    if (check_limits(gl, d, err))
        return 1;
    int depth = d->format == GL_DEPTH_COMPONENT32F;
    int n = depth ? 1 : d->colors < 1 ? 1 : d->colors > 2 ? 2 : d->colors;
    for (int i = 0; i < n; i++) {
        gl->GenTextures(1, &t->tex[i]);
        gl->BindTexture(GL_TEXTURE_2D, t->tex[i]);
        alloc_texture(gl, d, depth);
    }
    if (d->depth_stencil) {
        gl->GenRenderbuffers(1, &t->rb);
        gl->BindRenderbuffer(GL_RENDERBUFFER, t->rb);
        gl->RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, d->width, d->height);
    }
    gl->GenFramebuffers(1, &t->fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    if (depth) {
        gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t->tex[0], 0);
        GLenum none = GL_NONE;
        gl->DrawBuffers(1, &none);
    } else {
        for (int i = 0; i < n; i++)
            gl->FramebufferTexture2D(GL_FRAMEBUFFER, bufs[i], GL_TEXTURE_2D, t->tex[i], 0);
        gl->DrawBuffers(n, bufs);
    }
    if (t->rb)
        gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, t->rb);
    GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        cu_target_delete(t, gl);
        return cu_fail(err, "%s: framebuffer of %d x %d %s%s%s incomplete (status 0x%x)", d->name, d->width,
                       d->height, n == 2 ? "2 x " : "", format_name(d->format),
                       d->depth_stencil ? " + DEPTH24_STENCIL8" : "", (unsigned)st);
    }
    t->width = d->width;
    t->height = d->height;
    t->format = d->format;
    return 0;
}

void cu_target_delete(cu_target *t, const cu_gl *gl)
{
    for (int i = 0; i < 2; i++)
        if (t->tex[i])
            gl->DeleteTextures(1, &t->tex[i]);
    if (t->rb)
        gl->DeleteRenderbuffers(1, &t->rb);
    if (t->fbo)
        gl->DeleteFramebuffers(1, &t->fbo);
    memset(t, 0, sizeof *t);
}
