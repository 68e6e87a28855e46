/* src/gpu/pass_clock.c: GPU timestamps or the wall clock at the passes' boundaries (see pass_clock.h). */
#include "pass_clock.h"
#include <stdio.h>
#include <string.h>

#define TIMESTAMP 0x8E28          /* GL_TIMESTAMP(_EXT) */
#define QUERY_COUNTER_BITS 0x8864 /* GL_QUERY_COUNTER_BITS(_EXT) */
#define GPU_DISJOINT 0x8FBB       /* GL_GPU_DISJOINT_EXT */

void cu_pass_clock_init(cu_pass_clock *c, const cu_gl *gl, cu_get_proc_fn get, void *user, int is_gles,
                        int allow_timestamps)
{
    memset(c, 0, sizeof *c);
    c->mode = CU_PASS_CLOCK_WALL;
    c->gles = is_gles;
    if (!allow_timestamps)
        return;
    int has = 0;
    if (is_gles) {
        has = cu_gl_has_extension(gl, "GL_EXT_disjoint_timer_query");
    } else {
        const char *v = (const char *)gl->GetString(GL_VERSION);
        int major = 0, minor = 0;
        has = (v && sscanf(v, "%d.%d", &major, &minor) == 2 && (major > 3 || (major == 3 && minor >= 3))) ||
              cu_gl_has_extension(gl, "GL_ARB_timer_query");
    }
    if (!has)
        return;
    void *pc = cu_gl_optional(get, user, is_gles ? "glQueryCounterEXT" : "glQueryCounter");
    void *pg = cu_gl_optional(get, user, is_gles ? "glGetQueryObjectui64vEXT" : "glGetQueryObjectui64v");
    if (!pc || !pg)
        return;
    /* EXT_disjoint_timer_query lets an implementation have no timestamp counter (0 bits): then only TIME_ELAPSED */
    GLint bits = 0;
    while (gl->GetError() != GL_NO_ERROR) {
    }
    gl->GetQueryiv(TIMESTAMP, QUERY_COUNTER_BITS, &bits);
    if (gl->GetError() != GL_NO_ERROR || bits <= 0)
        return;
    memcpy(&c->counter, &pc, sizeof pc);
    memcpy(&c->get_ui64, &pg, sizeof pg);
    gl->GenQueries(CU_PASS_CLOCK_MARKS + 1, c->q);
    c->mode = CU_PASS_CLOCK_TIMESTAMPS;
}

void cu_pass_clock_free(cu_pass_clock *c, const cu_gl *gl)
{
    if (c->mode == CU_PASS_CLOCK_TIMESTAMPS && c->q[0])
        gl->DeleteQueries(CU_PASS_CLOCK_MARKS + 1, c->q);
    memset(c, 0, sizeof *c);
}

void cu_pass_clock_start(cu_pass_clock *c, const cu_gl *gl)
{
    c->n = 0;
    if (c->mode != CU_PASS_CLOCK_TIMESTAMPS)
        return;
    if (c->gles)
        (void)gl->GetIntegerv(GPU_DISJOINT, &(GLint){0}); /* reading the flag clears it */
    c->counter(c->q[0], TIMESTAMP);
}

void cu_pass_clock_boundary(cu_pass_clock *c, const cu_gl *gl, int pass)
{
    (void)gl;
    if (c->mode != CU_PASS_CLOCK_TIMESTAMPS)
        return;
    if (c->n == CU_PASS_CLOCK_MARKS) { /* out of queries: the time since the last one goes to this pass too */
        c->pass[c->n - 1] = pass;
        c->counter(c->q[c->n], TIMESTAMP);
        return;
    }
    c->pass[c->n++] = pass;
    c->counter(c->q[c->n], TIMESTAMP);
}

int cu_pass_clock_finish(cu_pass_clock *c, const cu_gl *gl, double *ms, int passes)
{
    if (c->mode != CU_PASS_CLOCK_TIMESTAMPS || c->n == 0)
        return 0;
    unsigned long long t[CU_PASS_CLOCK_MARKS + 1];
    for (int k = 0; k <= c->n; k++)
        c->get_ui64(c->q[k], GL_QUERY_RESULT, &t[k]); /* waits for the GPU: profiling is for measuring */
    if (c->gles) {
        GLint disjoint = 0;
        gl->GetIntegerv(GPU_DISJOINT, &disjoint);
        if (disjoint)
            return 1;
    }
    for (int k = 0; k < c->n; k++)
        if (c->pass[k] >= 0 && c->pass[k] < passes && t[k + 1] >= t[k])
            ms[c->pass[k]] += (double)(t[k + 1] - t[k]) * 1e-6;
    return 0;
}

const char *cu_pass_clock_describe(const cu_pass_clock *c)
{
    return c->mode == CU_PASS_CLOCK_TIMESTAMPS ? "GPU timestamps"
           : c->mode == CU_PASS_CLOCK_WALL     ? "wall clock, glFinish between passes"
                                               : "not chosen yet";
}
