/* src/core/budget.h: the frame budget's controller (quality.target_fps): from the time each frame took, the rung of
 * a ladder of cloud resolutions (quality.cloud_downsample) and update rates (quality.temporal_grid) the next frames
 * are drawn at. No GL: the renderer measures (src/gpu/frame_timer.c), this decides; tests/core/test_budget.c drives it
 * with costs of its own. */
#ifndef CU_BUDGET_H
#define CU_BUDGET_H

#define CU_BUDGET_RUNGS 16
#define CU_BUDGET_WINDOW 5    /* frames measured per decision (their median decides) */
#define CU_BUDGET_SETTLE 2    /* frames after a change that are not measured: a new grid starts with a whole frame,
                                 a new resolution with new targets */
#define CU_BUDGET_OVER 1.0    /* a median above target x this steps to the next coarser rung */
#define CU_BUDGET_ROOM 0.75   /* a median below target x this steps to the next finer rung ... */
#define CU_BUDGET_FITS 0.95   /* ... unless that rung measured above target x this, less than `retry` frames ago */
#define CU_BUDGET_RETRY 64    /* frames before a rung that did not fit is tried again; doubles each time it fails */
#define CU_BUDGET_RETRY_MAX 4096

typedef struct cu_budget_rung {
    int downsample; /* the cloud pass at 1/downsample of the output's resolution */
    int grid;       /* one cloud pixel of every grid x grid block marched a frame */
} cu_budget_rung;

typedef struct cu_budget {
    double target_ms;                  /* 1000 / quality.target_fps */
    int n, cur, from;                  /* rungs (finest first), the one in use, the one before it (-1: none) */
    cu_budget_rung rung[CU_BUDGET_RUNGS];
    double cost[CU_BUDGET_RUNGS];      /* the median last measured at each rung (ms); 0: never measured */
    long cost_frame[CU_BUDGET_RUNGS];  /* ... at which frame */
    double win[CU_BUDGET_WINDOW];      /* this window's frame times */
    int nwin, settle;
    long frame;                        /* frames observed */
    long retry;                        /* see CU_BUDGET_RETRY */
    double median_ms;                  /* the last window's median; 0 before the first */
} cu_budget;

/* The ladder from the finest (min_d, min_g) to the coarsest (max_d, max_g) rung: the resolution first halves (when
 * min_d is 1 and max_d allows it; the depth-aware upsampling costs little of the picture), then the grid grows
 * (a still view converges to the full picture), then the resolution falls further. The maxima are raised to the
 * minima. The controller starts at the finest rung. */
void cu_budget_init(cu_budget *b, double target_fps, int min_d, int min_g, int max_d, int max_g);
/* One frame's time in milliseconds; ignored unless finite and positive. Returns 1 when the rung changed (b->cur,
 * b->median_ms says why), else 0. */
int cu_budget_observe(cu_budget *b, double ms);
#endif
