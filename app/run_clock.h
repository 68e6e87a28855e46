/* app/run_clock.h: `cumulo run --clock` in the program: reads the wall and monotonic clocks, sets the renderer's sun
 * and scene time from them, and prints the clock lines (the arithmetic is platform/input/clock_control.c's). */
#ifndef CU_APP_RUN_CLOCK_H
#define CU_APP_RUN_CLOCK_H
#include "cumulo.h"
#include "clock_control.h"
#include <stdint.h>

/* The sun follows the time the clock shows, the clouds the monotonic time on from the scene's. */
typedef struct run_clock {
    cu_clock_ctl ctl;
    double lat, lon;                /* the scene's [sun] place */
    double scene_t0;                /* the scene time at the start */
    uint64_t t0;                    /* CLOCK_MONOTONIC at the start, ns */
    double aimed;                   /* the shown second the sun was last set for (NAN: none yet) */
    char utc[32];                   /* the same as ISO 8601 */
    int sun_failing, time_failing;  /* the last try failed: said once, not every frame */
} run_clock;

/* --clock-offset SECONDS or --time-scale K (opt: the option's name) into *ctl: 0, or 1 after printing why not. */
int  run_clock_option(cu_clock_ctl *ctl, const char *opt, const char *v);
/* Starts c with the settings of ctl at the scene's place (a warning when the scene gives none: 0 N 0 E) and the
 * renderer's scene time, sets the sun for the time shown and prints "clock ... source=start" on stderr. */
void run_clock_start(run_clock *c, const cu_clock_ctl *ctl, const cu_scene *scene, const char *scene_path,
                     cu_renderer *r);
/* Before each frame: the sun for the second shown now (when it is a new one), the clouds at the scene time. */
void run_clock_tick(run_clock *c, cu_renderer *r);
/* One input action: turns, the button and 'offset' move the time shown (a "clock ... source=S" line on stderr),
 * 'status' prints "status utc=... frames=N" on stdout, the sun's angles are refused with a line saying why. */
void run_clock_action(run_clock *c, const cu_action *a, const char *source, cu_renderer *r, long frames);
/* The header's "Sun:" lines: clock mode, the time shown, the place, the offsets, the sun. */
void run_clock_header(const run_clock *c, const cu_renderer *r);

#endif
