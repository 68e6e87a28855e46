/* platform/input/quadrature.c: quadrature decoding of a mechanical rotary encoder and push-button debouncing, as pure
 * state machines over timestamped levels (the GPIO and test code feed them; nothing here does I/O). */
#include "quadrature.h"

/* Position of each level pair (A<<1 | B) on the Gray-code cycle 11 -> 01 -> 00 -> 10 -> 11 (clockwise). Two
 * positions apart means both contacts changed at once: impossible for a real turn, so either an edge was missed
 * or it is noise. This table is the whole transition matrix: step = (pos[to] - pos[from]) mod 4. */
static const int cycle_pos[4] = { 2, 1, 3, 0 };

static int step_between(unsigned from, unsigned to)
{
    int d = (cycle_pos[to & 3] - cycle_pos[from & 3] + 4) % 4;
    return d == 3 ? -1 : d; /* 0 none, 1 clockwise, -1 counter-clockwise, 2 both changed */
}

static int is_rest(const cu_quad *q, unsigned ab)
{
    switch (q->cfg.steps_per_detent) {
    case 1:  return 1;
    case 2:  return ab == q->rest || ab == (q->rest ^ 3u); /* half-cycle encoders rest at 11 and 00 */
    default: return ab == q->rest;
    }
}

void cu_quad_init(cu_quad *q, const cu_quad_config *cfg, int a, int b)
{
    cu_quad z = {0};
    *q = z;
    if (cfg)
        q->cfg = *cfg;
    if (q->cfg.steps_per_detent != 1 && q->cfg.steps_per_detent != 2)
        q->cfg.steps_per_detent = 4;
    if (!q->cfg.glitch_ns)
        q->cfg.glitch_ns = 1000000u;
    if (!q->cfg.momentum_ns)
        q->cfg.momentum_ns = 100000000u;
    q->ab = (unsigned)((a ? 2 : 0) | (b ? 1 : 0));
    /* The knob is in a detent when the program starts (a hand is not on it), so that is the rest position:
     * this covers encoders that rest at 11 and those that rest at 00 without a setting. */
    q->rest = q->ab;
}

int cu_quad_feed(cu_quad *q, int a, int b, uint64_t t_ns)
{
    unsigned cur = (unsigned)((a ? 2 : 0) | (b ? 1 : 0));
    if (!q->started) {
        q->started = 1;
        q->t_last = q->t_left_rest = t_ns;
    }
    if (cur == q->ab)
        return 0; /* an edge whose partner was lost, or a repeated sample: no movement visible */

    uint64_t dt = t_ns > q->t_last ? t_ns - q->t_last : 0;
    int was_rest = is_rest(q, q->ab);
    int d = step_between(q->ab, cur);
    int rejected = 0;
    if (q->pending) {
        /* The jump before this was taken as a missed edge; a change right after it means it was the start of a
         * noise burst instead: take the guess back (even if it completed a detent, the count comes out right
         * once the real turn passes that detent). */
        if (dt < q->cfg.glitch_ns)
            q->acc -= q->pending;
        q->pending = 0;
    }
    if (d == 2) {
        /* Both contacts changed: a real turn passes through the state between, so one edge was missed. Its
         * direction is only known from momentum: the knob was turning (a recent valid step) and this is not a
         * noise burst (edges microseconds apart). Otherwise reject it: the count does not move. */
        int dir = q->acc > 0 ? 1 : q->acc < 0 ? -1 : q->last_dir;
        uint64_t since_step = t_ns > q->t_step ? t_ns - q->t_step : 0;
        if (dt >= q->cfg.glitch_ns && dir != 0 && since_step <= q->cfg.momentum_ns) {
            q->acc += 2 * dir;
            q->pending = 2 * dir;
            q->inferred++;
        } else {
            q->invalid++;
            rejected = 1;
        }
    } else {
        /* Bounce on one contact walks back and forth between two neighbours: +1 -1 +1 sums to the true move. */
        q->acc += d;
        q->last_dir = d;
        q->t_step = t_ns;
    }
    /* With one step per detent the cycle is the step itself, so it starts at the previous change. */
    uint64_t left = q->cfg.steps_per_detent == 1 ? q->t_last : q->t_left_rest;
    if (was_rest)
        q->t_left_rest = t_ns;
    q->t_last = t_ns;
    q->ab = cur; /* the levels are the truth; only the count is guessed */
    if (!is_rest(q, cur) || rejected)
        return 0; /* a rejected jump into the detent position says nothing about how far the knob went */

    /* Back in a detent: whole detents travelled since the last one. Truncation (not rounding) means a half cycle
     * left by a rejected jump never turns into a count of its own. */
    int det = q->acc / q->cfg.steps_per_detent;
    q->acc = 0;
    uint64_t cycle = t_ns > left ? t_ns - left : 0;
    if (det != 0 && cycle < q->cfg.glitch_ns) {
        /* A whole Gray cycle faster than a hand can turn: electrical noise that happened to wind around. */
        q->glitches++;
        return 0;
    }
    return det;
}

void cu_quad_sort_edges(cu_quad_edge *e, size_t n)
{
    /* Insertion sort: n is a read's worth of events (tens), and it is stable, which keeps each line's own order. */
    for (size_t i = 1; i < n; i++) {
        cu_quad_edge x = e[i];
        size_t j = i;
        while (j > 0 && e[j - 1].t_ns > x.t_ns) {
            e[j] = e[j - 1];
            j--;
        }
        e[j] = x;
    }
}

int cu_quad_feed_edges(cu_quad *q, cu_quad_edge *edges, size_t n)
{
    int det = 0;
    cu_quad_sort_edges(edges, n);
    for (size_t i = 0; i < n;) {
        int a = (q->ab >> 1) & 1, b = q->ab & 1;
        uint64_t t = edges[i].t_ns;
        for (; i < n && edges[i].t_ns == t; i++) {
            if (edges[i].line == 0)
                a = edges[i].level != 0;
            else
                b = edges[i].level != 0;
        }
        det += cu_quad_feed(q, a, b, t);
    }
    return det;
}

void cu_button_init(cu_button *b, uint64_t debounce_ns, int level)
{
    b->debounce_ns = debounce_ns ? debounce_ns : 20000000u;
    b->level = level != 0;
    b->t_change = 0;
    b->started = 0;
}

int cu_button_feed(cu_button *b, int level, uint64_t t_ns)
{
    level = level != 0;
    if (level == b->level)
        return 0;
    if (b->started && t_ns - b->t_change < b->debounce_ns && t_ns >= b->t_change)
        return 0; /* contact bounce right after an accepted change */
    b->started = 1;
    b->level = level;
    b->t_change = t_ns;
    return level == 0; /* pull-up: pressed pulls the line low */
}
