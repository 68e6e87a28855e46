/* src/gpu/profile.h: the renderer timing its own passes (cu_renderer_set_profiling, src/gpu/profile.c). */
#ifndef CU_PROFILE_H
#define CU_PROFILE_H
#include "renderer.h"

/* At the frame's start: the times zeroed, the clock started (nothing when profiling is off). */
void cu_profile_begin(cu_renderer *r);
/* At the end of a pass: the time since the last mark goes to `pass` (CU_PASS_*). */
void cu_profile_mark(cu_renderer *r, int pass);
/* After the frame (frame_ok 0: it failed, its times are dropped): GPU timestamps are read back, waiting for them. */
void cu_profile_end(cu_renderer *r, int frame_ok);
#endif
