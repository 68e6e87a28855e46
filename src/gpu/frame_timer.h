/* src/gpu/frame_timer.h: what a frame of cu_render costs, for the frame budget (quality.target_fps): GPU timer
 * queries where the context has them (EXT_disjoint_timer_query on GLES, GL 3.3 on desktop GL), read back frames
 * later without waiting; else the wall clock around the frame and a glFinish at its end. */
#ifndef CU_FRAME_TIMER_H
#define CU_FRAME_TIMER_H
#include "gl.h"

#define CU_FRAME_TIMER_QUERIES 4 /* frames in flight before a result is read back */

typedef void (*cu_get_query_ui64)(GLuint id, GLenum pname, unsigned long long *value);

typedef enum cu_timer_mode { CU_TIMER_QUERY, CU_TIMER_WALL } cu_timer_mode;

typedef struct cu_frame_timer {
    cu_timer_mode mode;
    int gles;                         /* the disjoint flag exists (GLES's extension) */
    cu_get_query_ui64 get_ui64;
    GLuint q[CU_FRAME_TIMER_QUERIES];
    int head, pending;                /* the next query to begin; how many ended and not read (oldest: head - pending) */
    int active;                       /* a query or a wall-clock frame is open */
    double t0, wall_ms;               /* CU_TIMER_WALL: the frame's start, its time (< 0: none to give) */
} cu_frame_timer;

/* Chooses the mode (allow_queries 0: the wall clock whatever the context has) and makes the queries. */
void cu_frame_timer_init(cu_frame_timer *t, const cu_gl *gl, cu_get_proc_fn get, void *user, int is_gles,
                         int allow_queries);
void cu_frame_timer_free(cu_frame_timer *t, const cu_gl *gl);
/* Around one frame's GL work. A frame whose query cannot begin (all in flight, or the host has a timer query of its
 * own open) goes unmeasured. */
void cu_frame_timer_begin(cu_frame_timer *t, const cu_gl *gl);
void cu_frame_timer_end(cu_frame_timer *t, const cu_gl *gl);
/* A measured frame's milliseconds, oldest first: 1 and *ms when one is ready, 0 when none is (never waits). Results
 * the GPU marks disjoint (a power change, a reset) are dropped. */
int cu_frame_timer_poll(cu_frame_timer *t, const cu_gl *gl, double *ms);
const char *cu_frame_timer_describe(const cu_frame_timer *t);
#endif
