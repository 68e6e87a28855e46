/* src/gpu/frame_timer.c: a frame's cost for the frame budget (see frame_timer.h). Queries are read only when
 * GL_QUERY_RESULT_AVAILABLE says so: the budget reacts a few frames late rather than stalling the pipeline. */
#include "frame_timer.h"
#include <stdio.h>
#include <string.h>
#include <time.h>

#define TIME_ELAPSED 0x88BF /* GL_TIME_ELAPSED(_EXT) */
#define GPU_DISJOINT 0x8FBB /* GL_GPU_DISJOINT_EXT */

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

void cu_frame_timer_init(cu_frame_timer *t, const cu_gl *gl, cu_get_proc_fn get, void *user, int is_gles,
                         int allow_queries)
{
    memset(t, 0, sizeof *t);
    t->mode = CU_TIMER_WALL;
    t->gles = is_gles;
    t->wall_ms = -1;
    int has = 0;
    const char *v = (const char *)gl->GetString(GL_VERSION);
    int major = 0, minor = 0;
    if (is_gles)
        has = cu_gl_has_extension(gl, "GL_EXT_disjoint_timer_query");
    else
        has = (v && sscanf(v, "%d.%d", &major, &minor) == 2 && (major > 3 || (major == 3 && minor >= 3))) ||
              cu_gl_has_extension(gl, "GL_ARB_timer_query");
    void *p = has && allow_queries ? cu_gl_optional(get, user, is_gles ? "glGetQueryObjectui64vEXT"
                                                                       : "glGetQueryObjectui64v") : NULL;
    if (!p)
        return;
    memcpy(&t->get_ui64, &p, sizeof p);
    gl->GenQueries(CU_FRAME_TIMER_QUERIES, t->q);
    t->mode = CU_TIMER_QUERY;
    if (t->gles)
        (void)gl->GetIntegerv(GPU_DISJOINT, &(GLint){0}); /* reading the flag clears it */
}

void cu_frame_timer_free(cu_frame_timer *t, const cu_gl *gl)
{
    if (t->mode == CU_TIMER_QUERY && t->q[0])
        gl->DeleteQueries(CU_FRAME_TIMER_QUERIES, t->q);
    memset(t, 0, sizeof *t);
}

void cu_frame_timer_begin(cu_frame_timer *t, const cu_gl *gl)
{
    t->active = 0;
    if (t->mode == CU_TIMER_WALL) {
        t->t0 = now_ms();
        t->active = 1;
        return;
    }
    GLint open = 0;
    gl->GetQueryiv(TIME_ELAPSED, GL_CURRENT_QUERY, &open);
    if (open || t->pending == CU_FRAME_TIMER_QUERIES)
        return; /* the host times something of its own (queries of a target do not nest), or all are in flight */
    gl->BeginQuery(TIME_ELAPSED, t->q[t->head]);
    t->active = 1;
}

void cu_frame_timer_end(cu_frame_timer *t, const cu_gl *gl)
{
    if (!t->active)
        return;
    t->active = 0;
    if (t->mode == CU_TIMER_WALL) {
        gl->Finish();
        t->wall_ms = now_ms() - t->t0;
        return;
    }
    gl->EndQuery(TIME_ELAPSED);
    t->head = (t->head + 1) % CU_FRAME_TIMER_QUERIES;
    t->pending++;
}

int cu_frame_timer_poll(cu_frame_timer *t, const cu_gl *gl, double *ms)
{
    if (t->mode == CU_TIMER_WALL) {
        if (t->wall_ms < 0)
            return 0;
        *ms = t->wall_ms;
        t->wall_ms = -1;
        return 1;
    }
    if (t->pending == 0)
        return 0;
    GLuint q = t->q[(t->head - t->pending + CU_FRAME_TIMER_QUERIES) % CU_FRAME_TIMER_QUERIES];
    GLuint ready = 0;
    gl->GetQueryObjectuiv(q, GL_QUERY_RESULT_AVAILABLE, &ready);
    if (!ready)
        return 0;
    unsigned long long ns = 0;
    t->get_ui64(q, GL_QUERY_RESULT, &ns);
    t->pending--;
    GLint disjoint = 0;
    if (t->gles)
        gl->GetIntegerv(GPU_DISJOINT, &disjoint);
    if (disjoint) { /* every result in flight spans the event: none of them is a frame's cost */
        t->pending = 0;
        return 0;
    }
    *ms = (double)ns * 1e-6;
    return 1;
}

const char *cu_frame_timer_describe(const cu_frame_timer *t)
{
    if (t->mode == CU_TIMER_WALL)
        return "the wall clock around each frame, which ends with glFinish (no GPU timer queries)";
    return t->gles ? "GPU timer queries (GL_EXT_disjoint_timer_query)" : "GPU timer queries (GL_TIME_ELAPSED)";
}
