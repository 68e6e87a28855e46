/* tests/platform/test_quadrature.c: the quadrature decoder and button debouncer on synthetic edge traces (clean
 * turns at
 * several speeds, bounce on every edge, missed edges, noise bursts, simultaneous edges) with exact detent counts. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "quadrature.h"

#define US 1000u
#define MS 1000000u

/* Clockwise Gray sequence from the 11 detent: A falls, B falls, A rises, B rises. */
static const int cw_line[4] = { 0, 1, 0, 1 };
static const int cw_level[4] = { 0, 0, 1, 1 };

typedef struct trace {
    cu_quad_edge e[4096];
    size_t n;
    uint64_t t;
} trace;

static void edge(trace *tr, int line, int level, uint64_t dt)
{
    tr->t += dt;
    tr->e[tr->n].line = line;
    tr->e[tr->n].level = level;
    tr->e[tr->n].t_ns = tr->t;
    tr->n++;
}

/* Quarter steps: dir +1 clockwise, -1 counter-clockwise (the same edges in reverse order with opposite levels).
 * bounce: extra toggles after each edge, 20 us apart, ending at the edge's level. */
static void steps(trace *tr, int *phase, int dir, int count, uint64_t interval, int bounce)
{
    for (int i = 0; i < count; i++) {
        int line, level;
        if (dir > 0) {
            line = cw_line[*phase];
            level = cw_level[*phase];
            *phase = (*phase + 1) % 4;
        } else {
            *phase = (*phase + 3) % 4;
            line = cw_line[*phase];
            level = !cw_level[*phase];
        }
        edge(tr, line, level, interval);
        for (int k = 0; k < bounce; k++) {
            edge(tr, line, !level, 20 * US);
            edge(tr, line, level, 20 * US);
        }
    }
}

static int run(trace *tr, int steps_per_detent)
{
    cu_quad q;
    cu_quad_config cfg = { .steps_per_detent = steps_per_detent };
    cu_quad_init(&q, &cfg, 1, 1);
    return cu_quad_feed_edges(&q, tr->e, tr->n);
}

static void test_clean_turns_at_several_speeds(void **state)
{
    (void)state;
    static const uint64_t intervals[] = { 50 * MS, 10 * MS, 2500 * US, 400 * US };
    for (size_t s = 0; s < sizeof intervals / sizeof intervals[0]; s++) {
        for (int dir = -1; dir <= 1; dir += 2) {
            static trace tr;
            tr.n = 0; tr.t = 1000 * MS;
            int phase = 0;
            steps(&tr, &phase, dir, 4 * 7, intervals[s], 0);
            assert_int_equal(run(&tr, 4), 7 * dir);
        }
    }
}

static void test_turn_back_and_forth(void **state)
{
    (void)state;
    static trace tr;
    tr.n = 0; tr.t = 0;
    int phase = 0;
    steps(&tr, &phase, 1, 12, 5 * MS, 0);   /* 3 detents clockwise */
    steps(&tr, &phase, -1, 4, 5 * MS, 0);   /* 1 back */
    steps(&tr, &phase, 1, 2, 5 * MS, 0);    /* half way into the next detent... */
    steps(&tr, &phase, -1, 2, 5 * MS, 0);   /* ...and back out: no count */
    assert_int_equal(run(&tr, 4), 2);
}

static void test_bounce_on_every_edge(void **state)
{
    (void)state;
    for (int dir = -1; dir <= 1; dir += 2) {
        for (int b = 1; b <= 3; b++) {
            static trace tr;
            tr.n = 0; tr.t = 0;
            int phase = 0;
            steps(&tr, &phase, dir, 4 * 5, 8 * MS, b);
            assert_int_equal(run(&tr, 4), 5 * dir);
        }
    }
}

static void test_half_step_encoder(void **state)
{
    (void)state;
    static trace tr;
    tr.n = 0; tr.t = 0;
    int phase = 0;
    steps(&tr, &phase, 1, 10, 5 * MS, 1);
    assert_int_equal(run(&tr, 2), 5);
}

/* A missed edge seen as levels: the state between two samples is skipped (both contacts changed). */
static void test_missed_edge_in_level_samples(void **state)
{
    (void)state;
    static const int cw_ab[4] = { 1, 0, 2, 3 }; /* A<<1|B after each clockwise step from 11 */
    for (int skip = 1; skip < 11; skip++) { /* not the last: a trace must end in a detent */
        cu_quad q;
        cu_quad_init(&q, NULL, 1, 1);
        int det = 0;
        uint64_t t = 0;
        for (int i = 0; i < 12; i++) {
            t += 6 * MS;
            if (i == skip)
                continue;
            det += cu_quad_feed(&q, cw_ab[i % 4] >> 1, cw_ab[i % 4] & 1, t);
        }
        assert_int_equal(det, 3);
        assert_int_equal(q.inferred, 1);
    }
    /* Counter-clockwise too. */
    static const int ccw_ab[4] = { 2, 0, 1, 3 };
    cu_quad q;
    cu_quad_init(&q, NULL, 1, 1);
    int det = 0;
    uint64_t t = 0;
    for (int i = 0; i < 8; i++) {
        t += 6 * MS;
        if (i == 5)
            continue;
        det += cu_quad_feed(&q, ccw_ab[i % 4] >> 1, ccw_ab[i % 4] & 1, t);
    }
    assert_int_equal(det, -2);
}

/* An edge whose opposite edge was lost (interrupt coalesced during bounce) arrives with the level the line already
 * has: no movement, and the count stays right. */
static void test_duplicate_edge_is_ignored(void **state)
{
    (void)state;
    static trace tr;
    tr.n = 0; tr.t = 0;
    int phase = 0;
    steps(&tr, &phase, 1, 2, 5 * MS, 0);
    edge(&tr, 1, 0, 30 * US); /* B again low */
    steps(&tr, &phase, 1, 6, 5 * MS, 0);
    assert_int_equal(run(&tr, 4), 2);
}

static void test_noise_burst_at_rest(void **state)
{
    (void)state;
    /* Random-looking chatter on both lines 15 us apart, ending where it started: nothing moved. */
    static const int burst[][2] = { {0, 0}, {1, 0}, {0, 1}, {1, 1}, {0, 0}, {0, 1}, {1, 0}, {1, 1}, {0, 1}, {1, 1} };
    static trace tr;
    tr.n = 0; tr.t = 5000 * MS;
    for (size_t i = 0; i < sizeof burst / sizeof burst[0]; i++)
        edge(&tr, burst[i][0], burst[i][1], 15 * US);
    assert_int_equal(run(&tr, 4), 0);

    /* A burst that happens to wind a whole Gray cycle in 60 us: far too fast for a hand. */
    tr.n = 0; tr.t = 5000 * MS;
    int phase = 0;
    steps(&tr, &phase, 1, 4, 15 * US, 0);
    cu_quad q;
    cu_quad_init(&q, NULL, 1, 1);
    assert_int_equal(cu_quad_feed_edges(&q, tr.e, tr.n), 0);
    assert_int_equal(q.glitches, 1);
}

static void test_noise_burst_during_turn(void **state)
{
    (void)state;
    static trace tr;
    tr.n = 0; tr.t = 0;
    int phase = 0;
    steps(&tr, &phase, 1, 6, 5 * MS, 0);
    /* Both lines chatter for a moment (EMI), then settle at the levels they had. */
    int a = 0, b = 0; /* after 6 clockwise steps from 11: 01, 00, 10, 11, 01, 00 */
    for (int k = 0; k < 6; k++) {
        edge(&tr, 0, !a, 10 * US);
        edge(&tr, 1, !b, 0);      /* same timestamp: simultaneous */
        edge(&tr, 0, a, 10 * US);
        edge(&tr, 1, b, 0);
    }
    steps(&tr, &phase, 1, 6, 5 * MS, 0);
    assert_int_equal(run(&tr, 4), 3);
}

static void test_simultaneous_edges(void **state)
{
    (void)state;
    /* At rest with no turn going on, both contacts changing together has no direction: rejected. */
    cu_quad q;
    cu_quad_init(&q, NULL, 1, 1);
    cu_quad_edge e[] = { {0, 0, 10 * MS}, {1, 0, 10 * MS}, {0, 1, 30 * MS}, {1, 1, 30 * MS} };
    assert_int_equal(cu_quad_feed_edges(&q, e, 4), 0);
    assert_true(q.invalid >= 1);

    /* During a steady turn the pair stands for the two steps between (one edge reported late): counted. */
    static trace tr;
    tr.n = 0; tr.t = 0;
    int phase = 0;
    steps(&tr, &phase, 1, 5, 6 * MS, 0);            /* 1 detent + first step of the next */
    edge(&tr, 1, 0, 6 * MS);                         /* B falls ... */
    edge(&tr, 0, 1, 0);                              /* ... and A rises at the same instant */
    phase = 3;
    steps(&tr, &phase, 1, 1, 6 * MS, 0);            /* B rises: back in a detent */
    assert_int_equal(run(&tr, 4), 2);
}

static void test_unsorted_edges_from_two_queues(void **state)
{
    (void)state;
    /* libgpiod v1 reads each line's queue separately: all of A's edges, then all of B's. */
    static trace tr;
    tr.n = 0; tr.t = 0;
    int phase = 0;
    steps(&tr, &phase, 1, 8, 5 * MS, 0);
    cu_quad_edge split[16];
    size_t n = 0;
    for (int line = 0; line < 2; line++)
        for (size_t i = 0; i < tr.n; i++)
            if (tr.e[i].line == line)
                split[n++] = tr.e[i];
    cu_quad q;
    cu_quad_init(&q, NULL, 1, 1);
    assert_int_equal(cu_quad_feed_edges(&q, split, n), 2);
}

static void test_rest_at_00(void **state)
{
    (void)state;
    /* Encoders that rest with both contacts closed (00): the start state is the detent. */
    static const int cw_from_00[4] = { 2, 3, 1, 0 };
    cu_quad q;
    cu_quad_init(&q, NULL, 0, 0);
    int det = 0;
    for (int i = 0; i < 8; i++)
        det += cu_quad_feed(&q, cw_from_00[i % 4] >> 1, cw_from_00[i % 4] & 1, (uint64_t)(i + 1) * 5 * MS);
    assert_int_equal(det, 2);
}

static void test_button_debounce(void **state)
{
    (void)state;
    cu_button b;
    cu_button_init(&b, 0, 1);
    int presses = 0;
    uint64_t t = 100 * MS;
    for (int p = 0; p < 3; p++) {
        presses += cu_button_feed(&b, 0, t);
        presses += cu_button_feed(&b, 1, t + 200 * US); /* bounce */
        presses += cu_button_feed(&b, 0, t + 400 * US);
        presses += cu_button_feed(&b, 1, t + 150 * MS); /* release */
        presses += cu_button_feed(&b, 0, t + 150 * MS + 300 * US);
        presses += cu_button_feed(&b, 1, t + 150 * MS + 600 * US);
        t += 500 * MS;
    }
    assert_int_equal(presses, 3);
}

/* Deterministic pseudo-random traces (LCG; no libc rand, whose sequence differs between C libraries): whole detents
 * either way at hand speeds, bounce of 0-3 toggles on any edge, and noise bursts on both lines while the knob rests.
 * The decoder must count exactly the detents turned. */
static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

static void test_random_traces(void **state)
{
    (void)state;
    uint32_t seed = 12345;
    for (int trial = 0; trial < 200; trial++) {
        static trace tr;
        tr.n = 0; tr.t = 1000 * MS;
        int phase = 0, truth = 0;
        for (int d = 0; d < 12 && tr.n < 3500; d++) {
            int dir = (lcg(&seed) & 1) ? 1 : -1;
            uint64_t interval = 2 * MS + (lcg(&seed) % (18 * MS));
            for (int q = 0; q < 4; q++)
                steps(&tr, &phase, dir, 1, interval, (int)(lcg(&seed) % 4));
            truth += dir;
            if (lcg(&seed) % 3 == 0) {
                /* At rest (levels 11): a burst of 2-8 glitches 5-50 us apart on both lines, back to 11. */
                tr.t += 30 * MS;
                int k = 2 + (int)(lcg(&seed) % 7);
                for (int g = 0; g < k; g++) {
                    int line = (int)(lcg(&seed) & 1);
                    edge(&tr, line, 0, 5 * US + lcg(&seed) % (45 * US));
                    if (lcg(&seed) & 1)
                        edge(&tr, !line, 0, 0); /* simultaneous */
                    edge(&tr, 0, 1, 5 * US + lcg(&seed) % (45 * US));
                    edge(&tr, 1, 1, 0);
                }
                tr.t += 30 * MS;
            }
        }
        int got = run(&tr, 4);
        if (got != truth)
            fail_msg("trial %d: counted %d detents, turned %d", trial, got, truth);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clean_turns_at_several_speeds),
        cmocka_unit_test(test_turn_back_and_forth),
        cmocka_unit_test(test_bounce_on_every_edge),
        cmocka_unit_test(test_half_step_encoder),
        cmocka_unit_test(test_missed_edge_in_level_samples),
        cmocka_unit_test(test_duplicate_edge_is_ignored),
        cmocka_unit_test(test_noise_burst_at_rest),
        cmocka_unit_test(test_noise_burst_during_turn),
        cmocka_unit_test(test_simultaneous_edges),
        cmocka_unit_test(test_unsorted_edges_from_two_queues),
        cmocka_unit_test(test_rest_at_00),
        cmocka_unit_test(test_button_debounce),
        cmocka_unit_test(test_random_traces),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
