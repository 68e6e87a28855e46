/* platform/input/quadrature.h: pure decoders for mechanical contacts: a rotary-encoder quadrature decoder that counts
 * detents and a push-button debouncer. No I/O: fed level samples or edges with timestamps, so traces test them. */
#ifndef CU_PLATFORM_QUADRATURE_H
#define CU_PLATFORM_QUADRATURE_H
#include <stddef.h>
#include <stdint.h>

/* Zero fields mean "default" (sokol-style). */
typedef struct cu_quad_config {
    int steps_per_detent;   /* quadrature steps between two detents: 4 (full cycle, KY-040 and most), 2 or 1; 0 = 4 */
    uint64_t glitch_ns;     /* shorter than this is contact noise, not a hand turning a knob; 0 = 1 ms */
    uint64_t momentum_ns;   /* a skipped state is inferred as a missed edge only this soon after a valid step; 0 = 100 ms */
} cu_quad_config;

typedef struct cu_quad {
    cu_quad_config cfg;
    unsigned ab;            /* current levels: bit 1 = A, bit 0 = B */
    unsigned rest;          /* the levels at a detent (the state at start-up: the knob rests in a detent) */
    int acc;                /* quarter steps moved since the last detent */
    int last_dir;           /* direction of the last valid step (+1 clockwise, -1 counter-clockwise, 0 none yet) */
    int pending;            /* quarter steps added by the last inferred missed edge, until the next change confirms it */
    uint64_t t_last;        /* time of the last level change */
    uint64_t t_step;        /* time of the last valid single step */
    uint64_t t_left_rest;   /* when the contacts last left the detent position */
    int started;            /* a timestamp has been seen */
    /* Diagnostics, counted for logs and tests. */
    unsigned long invalid;  /* both contacts changed at once and it could not be explained */
    unsigned long inferred; /* both contacts changed and it was taken as one missed edge */
    unsigned long glitches; /* detent cycles rejected as too fast to be a hand */
} cu_quad;

/* One edge from a GPIO line: line 0 = A, 1 = B; level after the edge; kernel timestamp. */
typedef struct cu_quad_edge {
    int line;
    int level;
    uint64_t t_ns;
} cu_quad_edge;

void cu_quad_init(cu_quad *q, const cu_quad_config *cfg, int a, int b);
/* Feeds the levels sampled at t_ns; returns the detents completed (+ clockwise, - counter-clockwise). */
int  cu_quad_feed(cu_quad *q, int a, int b, uint64_t t_ns);
/* Feeds edges: sorts them by timestamp (stable, so same-line order is kept), merges edges that carry the same
 * timestamp into one sample (the kernel saw them together; their order is meaningless), returns the detents. */
int  cu_quad_feed_edges(cu_quad *q, cu_quad_edge *edges, size_t n);
/* Stable in-place sort of edges by timestamp (v1 libgpiod delivers one queue per line). */
void cu_quad_sort_edges(cu_quad_edge *edges, size_t n);

/* Push button, active low (pull-up, contact to ground): reports a press once per debounced press. */
typedef struct cu_button {
    uint64_t debounce_ns;   /* 0 = 20 ms */
    int level;              /* debounced level */
    uint64_t t_change;      /* time of the last accepted change */
    int started;
} cu_button;
void cu_button_init(cu_button *b, uint64_t debounce_ns, int level);
/* Returns 1 when this edge is an accepted press, 0 otherwise. */
int  cu_button_feed(cu_button *b, int level, uint64_t t_ns);

#endif
