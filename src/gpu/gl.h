/* src/gpu/gl.h: GLES 3.0 entry points loaded through the caller's get_proc_address into a per-renderer table (no
 * globals, no link-time GL symbols, so one binary can drive EGL and OSMesa contexts), and shader build helpers. */
#ifndef CU_GL_H
#define CU_GL_H
#include <GLES3/gl3.h>
#include "cumulo.h"

#define CU_GL_FUNCS(X) \
    X(ActiveTexture, ACTIVETEXTURE) X(AttachShader, ATTACHSHADER) X(BeginQuery, BEGINQUERY) \
    X(BindBuffer, BINDBUFFER) X(BindFramebuffer, BINDFRAMEBUFFER) X(BindRenderbuffer, BINDRENDERBUFFER) X(BindSampler, BINDSAMPLER) \
    X(BindTexture, BINDTEXTURE) X(BindVertexArray, BINDVERTEXARRAY) X(BlendEquation, BLENDEQUATION) \
    X(BlendEquationSeparate, BLENDEQUATIONSEPARATE) X(BlendFunc, BLENDFUNC) X(BlendFuncSeparate, BLENDFUNCSEPARATE) \
    X(BufferData, BUFFERDATA) X(BufferSubData, BUFFERSUBDATA) \
    X(CheckFramebufferStatus, CHECKFRAMEBUFFERSTATUS) X(Clear, CLEAR) X(ClearBufferfv, CLEARBUFFERFV) \
    X(ClearColor, CLEARCOLOR) \
    X(ClearDepthf, CLEARDEPTHF) X(ClearStencil, CLEARSTENCIL) X(ColorMask, COLORMASK) X(CompileShader, COMPILESHADER) \
    X(CreateProgram, CREATEPROGRAM) X(CreateShader, CREATESHADER) X(DeleteBuffers, DELETEBUFFERS) \
    X(DeleteFramebuffers, DELETEFRAMEBUFFERS) X(DeleteProgram, DELETEPROGRAM) X(DeleteQueries, DELETEQUERIES) \
    X(DeleteRenderbuffers, DELETERENDERBUFFERS) X(DeleteSamplers, DELETESAMPLERS) X(DeleteShader, DELETESHADER) X(DeleteTextures, DELETETEXTURES) \
    X(DeleteVertexArrays, DELETEVERTEXARRAYS) X(DepthFunc, DEPTHFUNC) X(DepthMask, DEPTHMASK) \
    X(Disable, DISABLE) X(DrawArrays, DRAWARRAYS) X(DrawBuffers, DRAWBUFFERS) \
    X(DrawElementsInstanced, DRAWELEMENTSINSTANCED) X(Enable, ENABLE) \
    X(EnableVertexAttribArray, ENABLEVERTEXATTRIBARRAY) X(EndQuery, ENDQUERY) X(Finish, FINISH) X(Flush, FLUSH) \
    X(FramebufferRenderbuffer, FRAMEBUFFERRENDERBUFFER) X(FramebufferTexture2D, FRAMEBUFFERTEXTURE2D) \
    X(GenBuffers, GENBUFFERS) X(GenerateMipmap, GENERATEMIPMAP) X(GenFramebuffers, GENFRAMEBUFFERS) X(GenQueries, GENQUERIES) \
    X(GenRenderbuffers, GENRENDERBUFFERS) X(GenSamplers, GENSAMPLERS) X(GenTextures, GENTEXTURES) X(GenVertexArrays, GENVERTEXARRAYS) \
    X(GetBooleanv, GETBOOLEANV) X(GetError, GETERROR) X(GetFloatv, GETFLOATV) X(GetIntegerv, GETINTEGERV) X(GetProgramInfoLog, GETPROGRAMINFOLOG) \
    X(GetProgramiv, GETPROGRAMIV) X(GetQueryiv, GETQUERYIV) X(GetQueryObjectuiv, GETQUERYOBJECTUIV) X(GetShaderInfoLog, GETSHADERINFOLOG) \
    X(GetShaderiv, GETSHADERIV) X(GetString, GETSTRING) X(GetStringi, GETSTRINGI) \
    X(GetUniformLocation, GETUNIFORMLOCATION) X(IsEnabled, ISENABLED) X(LinkProgram, LINKPROGRAM) X(PixelStorei, PIXELSTOREI) \
    X(ReadPixels, READPIXELS) X(RenderbufferStorage, RENDERBUFFERSTORAGE) X(SamplerParameteri, SAMPLERPARAMETERI) X(Scissor, SCISSOR) \
    X(ShaderSource, SHADERSOURCE) X(StencilFunc, STENCILFUNC) X(StencilFuncSeparate, STENCILFUNCSEPARATE) \
    X(StencilMaskSeparate, STENCILMASKSEPARATE) X(StencilOp, STENCILOP) X(StencilOpSeparate, STENCILOPSEPARATE) \
    X(TexImage2D, TEXIMAGE2D) X(TexImage3D, TEXIMAGE3D) X(TexParameteri, TEXPARAMETERI) \
    X(Uniform1f, UNIFORM1F) X(Uniform1fv, UNIFORM1FV) X(Uniform1i, UNIFORM1I) X(Uniform2f, UNIFORM2F) X(Uniform2i, UNIFORM2I) \
    X(Uniform3f, UNIFORM3F) X(Uniform3fv, UNIFORM3FV) X(Uniform4f, UNIFORM4F) X(Uniform4fv, UNIFORM4FV) \
    X(UniformMatrix4fv, UNIFORMMATRIX4FV) X(UseProgram, USEPROGRAM) X(VertexAttribDivisor, VERTEXATTRIBDIVISOR) \
    X(VertexAttribPointer, VERTEXATTRIBPOINTER) X(Viewport, VIEWPORT)

#define CU_GL_MEMBER(name, NAME) PFNGL##NAME##PROC name;
typedef struct cu_gl {
    CU_GL_FUNCS(CU_GL_MEMBER)
} cu_gl;
#undef CU_GL_MEMBER

/* Loads every entry point; on failure names the first missing one. */
int cu_gl_load(cu_gl *gl, cu_get_proc_fn get, void *user, cu_error *err);
int cu_gl_has_extension(const cu_gl *gl, const char *name);
/* An entry point beyond GLES 3.0 (an extension's): NULL when the context lacks it. get NULL: the process's own. */
void *cu_gl_optional(cu_get_proc_fn get, void *user, const char *name);

typedef struct cu_shader_src {
    const char *name;   /* file name under shaders_gles/, for messages */
    const char *const *lines; /* one string per source line, each ending in '\n' */
    int nlines;
} cu_shader_src;
/* Looks up an embedded shader by file name. */
const cu_shader_src *cu_shader_find(const char *name);
/* Compiles and links vs + fs with `defines` (lines of "#define ...") inserted after #version. Errors name the
 * file and carry the driver's log. */
GLuint cu_gl_program(const cu_gl *gl, const char *vs_name, const char *fs_name, const char *defines, cu_error *err);
#endif
