/* tests/core/test_budget.c: the frame budget's controller (src/core/budget.c) driven by frame costs of the test's own:
 * the ladder's shape and bounds, convergence to the finest rung that fits, no swinging at the edge of the budget
 * under noise, a scene that gets heavier and lighter again, and measurements that are not numbers. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdint.h>
#include "budget.h"

static uint64_t rng_state = 0x2545f4914f6cdd1dULL;
static double urand(void) /* xorshift64*: failures reproduce */
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (double)((rng_state * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

/* A frame's cost at a rung: a fixed part and a part in proportion to the cloud pixels marched, +-noise. */
static double cost(const cu_budget *b, double fixed, double full, double noise)
{
    const cu_budget_rung *r = &b->rung[b->cur];
    double frac = 1.0 / (r->downsample * r->downsample * r->grid * r->grid);
    return (fixed + full * frac) * (1.0 + noise * (2.0 * urand() - 1.0));
}

/* Runs n frames; returns how many times the rung changed. */
static int run(cu_budget *b, int n, double fixed, double full, double noise)
{
    int changes = 0;
    for (int i = 0; i < n; i++)
        changes += cu_budget_observe(b, cost(b, fixed, full, noise));
    return changes;
}

static double rung_cost(const cu_budget *b, int i, double fixed, double full)
{
    const cu_budget_rung *r = &b->rung[i];
    return fixed + full / (r->downsample * r->downsample * r->grid * r->grid);
}

/* The finest rung whose noise-free cost fits the target. */
static int best_fit(const cu_budget *b, double fixed, double full)
{
    for (int i = 0; i < b->n; i++)
        if (rung_cost(b, i, fixed, full) <= b->target_ms)
            return i;
    return b->n - 1;
}

static void test_ladder(void **st)
{
    (void)st;
    cu_budget b;
    cu_budget_init(&b, 30, 1, 1, 4, 4);
    static const int want[][2] = {{1, 1}, {2, 1}, {2, 2}, {2, 3}, {2, 4}, {3, 4}, {4, 4}};
    assert_int_equal(b.n, 7);
    for (int i = 0; i < b.n; i++) {
        assert_int_equal(b.rung[i].downsample, want[i][0]);
        assert_int_equal(b.rung[i].grid, want[i][1]);
    }
    assert_int_equal(b.cur, 0);
    assert_true(fabs(b.target_ms - 1000.0 / 30) < 1e-12);
    /* the scene's own settings are the finest rung; maxima below them are raised to them */
    cu_budget_init(&b, 30, 2, 2, 1, 1);
    assert_int_equal(b.n, 1);
    assert_int_equal(b.rung[0].downsample, 2);
    assert_int_equal(b.rung[0].grid, 2);
    cu_budget_init(&b, 30, 1, 1, 1, 3); /* grid only */
    assert_int_equal(b.n, 3);
    assert_int_equal(b.rung[2].downsample, 1);
    assert_int_equal(b.rung[2].grid, 3);
    cu_budget_init(&b, 30, 3, 1, 4, 1); /* resolution only, from a third */
    assert_int_equal(b.n, 2);
    assert_int_equal(b.rung[1].downsample, 4);
    /* every rung marches no more pixels than the one before */
    cu_budget_init(&b, 30, 1, 1, 4, 4);
    for (int i = 1; i < b.n; i++)
        assert_true(b.rung[i].downsample >= b.rung[i - 1].downsample && b.rung[i].grid >= b.rung[i - 1].grid);
}

/* From the finest rung, a heavy scene steps down to the finest rung that fits, and stays there. */
static void test_converges_and_holds(void **st)
{
    (void)st;
    static const double fulls[] = {20, 60, 200, 800, 3000};
    for (unsigned k = 0; k < sizeof fulls / sizeof *fulls; k++) {
        cu_budget b;
        cu_budget_init(&b, 30, 1, 1, 4, 4);
        double fixed = 4, full = fulls[k];
        int want = best_fit(&b, fixed, full);
        run(&b, 7 * (b.n + 1), fixed, full, 0.05); /* a step takes settle + window frames */
        assert_int_equal(b.cur, want);
        int changes = run(&b, 2000, fixed, full, 0.05);
        if (changes) /* the only moves allowed: probes of the finer rung, each slower than the last */
            assert_true(changes <= 2 * 6);
        assert_int_equal(b.cur, want);
    }
}

/* At the edge of the budget, with 15 % noise: the controller must not swing between two rungs every few frames. */
static void test_no_swinging_at_the_edge(void **st)
{
    (void)st;
    cu_budget b;
    cu_budget_init(&b, 30, 1, 1, 2, 4);
    /* rung (2,1) costs 4 + 140/4 = 39 ms (over 33.3 by 17 %), rung (2,2) 12.75 ms (within by far: a finer rung
     * looks worth a try every time) */
    run(&b, 200, 4, 140, 0.15);
    int changes = run(&b, 10000, 4, 140, 0.15);
    /* probes of the rung that does not fit back off: 64, 128, ... 4096 frames; each costs two changes */
    assert_true(changes <= 2 * 8);
    assert_true(b.rung[b.cur].downsample == 2 && b.rung[b.cur].grid == 2);
}

/* The scene gets heavier (clouds fill the view), then lighter again: down, then back up to the finest rung. */
static void test_follows_the_load(void **st)
{
    (void)st;
    cu_budget b;
    cu_budget_init(&b, 20, 1, 1, 4, 4);
    run(&b, 100, 2, 20, 0.05);
    assert_int_equal(b.cur, 0);
    run(&b, 100, 2, 400, 0.05);
    int heavy = b.cur;
    assert_int_equal(heavy, best_fit(&b, 2, 400));
    assert_true(heavy > 0);
    /* lighter: the rungs above were measured slow, so the climb waits for their retry (at most 64 frames each) */
    run(&b, 64 * b.n + 7 * b.n, 2, 20, 0.05);
    assert_int_equal(b.cur, 0);
}

/* A target no rung can reach: the coarsest rung, and no changes after. A generous one: the finest, never moved. */
static void test_bounds(void **st)
{
    (void)st;
    cu_budget b;
    cu_budget_init(&b, 1000, 1, 1, 4, 4);
    run(&b, 200, 5, 500, 0.05);
    assert_int_equal(b.cur, b.n - 1);
    assert_int_equal(run(&b, 500, 5, 500, 0.05), 0);
    cu_budget_init(&b, 1, 1, 1, 4, 4);
    assert_int_equal(run(&b, 500, 5, 500, 0.05), 0);
    assert_int_equal(b.cur, 0);
}

/* NaN, infinities, zero and negative times (a timer query that failed, a clock that stepped) are not measurements. */
static void test_not_numbers(void **st)
{
    (void)st;
    cu_budget b;
    cu_budget_init(&b, 30, 1, 1, 4, 4);
    const double bad[] = {NAN, INFINITY, -INFINITY, 0.0, -5.0, -0.0};
    for (int i = 0; i < 600; i++)
        assert_int_equal(cu_budget_observe(&b, bad[i % 6]), 0);
    assert_int_equal(b.cur, 0);
    assert_int_equal(b.frame, 0);
    /* off (target 0): nothing moves whatever a frame costs */
    cu_budget_init(&b, 0, 1, 1, 4, 4);
    for (int i = 0; i < 100; i++)
        assert_int_equal(cu_budget_observe(&b, 1e6), 0);
    assert_int_equal(b.cur, 0);
}

/* One slow frame in a window (a map rebuild, a whole temporal frame) does not move the rung: the median decides. */
static void test_one_slow_frame(void **st)
{
    (void)st;
    cu_budget b;
    cu_budget_init(&b, 30, 1, 1, 4, 4);
    for (int i = 0; i < 500; i++)
        assert_int_equal(cu_budget_observe(&b, i % CU_BUDGET_WINDOW == 2 ? 400.0 : 20.0), 0);
    assert_int_equal(b.cur, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ladder),          cmocka_unit_test(test_converges_and_holds),
        cmocka_unit_test(test_no_swinging_at_the_edge), cmocka_unit_test(test_follows_the_load),
        cmocka_unit_test(test_bounds),          cmocka_unit_test(test_not_numbers),
        cmocka_unit_test(test_one_slow_frame),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
