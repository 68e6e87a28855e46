/* src/gpu/pass_clock.h: the clock cumulo bench --passes and cu_renderer_pass_times read: GPU timestamps where the
 * context has them (EXT_disjoint_timer_query's glQueryCounterEXT on GLES, GL 3.3 or ARB_timer_query on desktop GL),
 * else the wall clock between glFinish calls. Timestamps neither serialise the passes nor conflict with a
 * GL_TIME_ELAPSED query that is open around the frame (the frame budget's, or the host's own). */
#ifndef CU_PASS_CLOCK_H
#define CU_PASS_CLOCK_H
#include "frame_timer.h"
#include "gl.h"

#define CU_PASS_CLOCK_MARKS 24 /* pass boundaries one frame can time; later ones go to the last */

typedef enum cu_pass_clock_mode {
    CU_PASS_CLOCK_UNSET,      /* chosen by the first profiled frame */
    CU_PASS_CLOCK_WALL,       /* glFinish at every boundary, the CPU's clock */
    CU_PASS_CLOCK_TIMESTAMPS, /* a GL_TIMESTAMP query at every boundary, read at the frame's end */
} cu_pass_clock_mode;

typedef void (*cu_query_counter_fn)(GLuint id, GLenum target);

typedef struct cu_pass_clock {
    cu_pass_clock_mode mode;
    int gles;                         /* the disjoint flag exists (GLES's extension) */
    cu_query_counter_fn counter;
    cu_get_query_ui64 get_ui64;
    GLuint q[CU_PASS_CLOCK_MARKS + 1]; /* q[0] at the frame's start, q[k] at its k-th boundary */
    int pass[CU_PASS_CLOCK_MARKS];    /* the pass each boundary ends */
    int n;                            /* boundaries this frame */
} cu_pass_clock;

/* Chooses the mode once (allow_timestamps 0: the wall clock whatever the context has) and makes the queries; the
 * context must be current. */
void cu_pass_clock_init(cu_pass_clock *c, const cu_gl *gl, cu_get_proc_fn get, void *user, int is_gles,
                        int allow_timestamps);
void cu_pass_clock_free(cu_pass_clock *c, const cu_gl *gl);
/* A frame's start and its pass boundaries (timestamps: queries issued, nothing waited for). */
void cu_pass_clock_start(cu_pass_clock *c, const cu_gl *gl);
void cu_pass_clock_boundary(cu_pass_clock *c, const cu_gl *gl, int pass);
/* Timestamps: waits for the frame's queries and adds each pass's milliseconds into ms[]. Returns 0, or 1 when the
 * GPU says the results are not to be trusted (GPU_DISJOINT: a power change, a reset) and nothing was added. */
int cu_pass_clock_finish(cu_pass_clock *c, const cu_gl *gl, double *ms, int passes);
/* "GPU timestamps" or "wall clock, glFinish between passes" (or "not chosen yet"). */
const char *cu_pass_clock_describe(const cu_pass_clock *c);
#endif
