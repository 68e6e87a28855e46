/* src/core/budget.c: the frame budget's controller (see budget.h): windows of measured frames, a median each, and a
 * step along the ladder when the median leaves the band [ROOM, OVER] x target. A rung that was too slow is not tried
 * again for `retry` frames, which doubles on each failed try: at the edge of the budget the controller settles on the
 * finest rung that fits instead of swinging between two. */
#include "budget.h"
#include <math.h>
#include <string.h>

void cu_budget_init(cu_budget *b, double target_fps, int min_d, int min_g, int max_d, int max_g)
{
    memset(b, 0, sizeof *b);
    b->target_ms = target_fps > 0 ? 1000.0 / target_fps : 0;
    b->retry = CU_BUDGET_RETRY;
    b->from = -1;
    int d = min_d < 1 ? 1 : min_d, g = min_g < 1 ? 1 : min_g;
    if (max_d < d)
        max_d = d;
    if (max_g < g)
        max_g = g;
    for (;;) {
        b->rung[b->n++] = (cu_budget_rung){d, g};
        if (b->n == CU_BUDGET_RUNGS)
            break;
        if (d < 2 && d < max_d)
            d++;
        else if (g < max_g)
            g++;
        else if (d < max_d)
            d++;
        else
            break;
    }
}

static double median(const double *v, int n)
{
    double s[CU_BUDGET_WINDOW];
    memcpy(s, v, sizeof *v * (size_t)n);
    for (int a = 1; a < n; a++) /* insertion sort: five values */
        for (int b = a; b > 0 && s[b - 1] > s[b]; b--) {
            double t = s[b];
            s[b] = s[b - 1];
            s[b - 1] = t;
        }
    return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

static int move_to(cu_budget *b, int rung)
{
    b->from = b->cur;
    b->cur = rung;
    b->settle = CU_BUDGET_SETTLE;
    return 1;
}

int cu_budget_observe(cu_budget *b, double ms)
{
    if (!(ms > 0) || !isfinite(ms) || b->target_ms <= 0)
        return 0;
    b->frame++;
    if (b->settle > 0) {
        b->settle--;
        return 0;
    }
    b->win[b->nwin++] = ms;
    if (b->nwin < CU_BUDGET_WINDOW)
        return 0;
    b->nwin = 0;
    double m = median(b->win, CU_BUDGET_WINDOW), t = b->target_ms;
    int c = b->cur, probe = b->from == c + 1; /* this rung was tried from the coarser one */
    b->median_ms = m;
    b->cost[c] = m;
    b->cost_frame[c] = b->frame;
    if (m > CU_BUDGET_OVER * t) {
        if (probe) /* the finer rung did not fit: wait longer before the next try */
            b->retry = b->retry * 2 < CU_BUDGET_RETRY_MAX ? b->retry * 2 : CU_BUDGET_RETRY_MAX;
        return c + 1 < b->n ? move_to(b, c + 1) : 0;
    }
    if (probe)
        b->retry = CU_BUDGET_RETRY;
    if (m < CU_BUDGET_ROOM * t && c > 0) {
        int known_slow = b->cost[c - 1] > CU_BUDGET_FITS * t && b->frame - b->cost_frame[c - 1] < b->retry;
        if (!known_slow)
            return move_to(b, c - 1);
    }
    return 0;
}
