/* tests/core/test_ms_diffusion.c: src/core/ms_diffusion.c, multiple scattering as flux-limited diffusion on a grid
 * (ms.mode = diffusion). Against closed forms: a wide slab's first scattering takes all the sunlight its optical depth
 * stops, the sun overhead or slanted, the solve sends out exactly what the sunbeam put in (no light made or lost),
 * and its transmission is the Eddington (two-stream) value of a conservative slab within 10 %; a sphere lit from
 * above is mirror-symmetric about the sun's axis and brighter on top than at its base; the light leaves through the
 * true surface's area, not the staircase of cells that stands for it; a solve started from the last one (the sun
 * moved half a degree) takes fewer sweeps than one from nothing and finds the same light; a grid of 96 cells a side
 * settles within the renderer's budget; hostile grids and clouds stay finite. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "ms_diffusion.h"

/* A grid over the box lo..hi, `cells` along its longest side, holding nothing yet. */
static void empty_grid(cu_msd *g, vec3 lo, vec3 hi, int cells)
{
    cu_cloud cl;
    memset(&cl, 0, sizeof cl);
    cl.bounds_min = lo;
    cl.bounds_max = hi;
    cu_error e = {{0}};
    assert_int_equal(cu_msd_init(g, &cl, cells, &e), 0);
}

/* A slab of optical depth tau, `thick` cells thick, across a 2 km square, lit straight from above: the grid's cells
 * are filled directly (the density field is not what is tested here). */
static void slab(cu_msd *g, double tau, int thick)
{
    empty_grid(g, v3(-1000, -50, -1000), v3(1000, 50, 1000), 64);
    /* the grid keeps a quarter of its cells across the thin side: 15 here, of which `thick` hold cloud */
    assert_true(g->n[1] - 2 * CU_MSD_MARGIN >= thick);
    int j0 = (g->n[1] - thick) / 2;
    double ke = tau / (thick * g->h[1]);
    for (int k = CU_MSD_MARGIN; k < g->n[2] - CU_MSD_MARGIN; k++)
        for (int j = j0; j < j0 + thick; j++)
            for (int i = CU_MSD_MARGIN; i < g->n[0] - CU_MSD_MARGIN; i++)
                g->ke[cu_msd_at(g, i, j, k)] = (float)ke;
}

/* The eddington transmission of a conservative slab in collimated normal light (Meador & Weaver 1980, gamma_1 =
 * 3 (1 - g) / 4, gamma_3 = (2 - 3 g) / 4 at mu_0 = 1): 1 - R, R = (gamma_1 tau - (1 - e^-tau) / 4) / (1 + gamma_1 tau). */
static double eddington_t(double tau, double g)
{
    double g1 = 0.75 * (1.0 - g);
    return 1.0 - (g1 * tau - 0.25 * (1.0 - exp(-tau))) / (1.0 + g1 * tau);
}

static void test_slab_energy_and_transmission(void **st)
{
    (void)st;
    static const struct { double tau, g; int thick; } cases[] = {{20, 0.85, 8}, {40, 0.85, 12}, {20, 0.5, 8}};
    for (size_t n = 0; n < sizeof cases / sizeof cases[0]; n++) {
        cu_msd g;
        slab(&g, cases[n].tau, cases[n].thick);
        cu_msd_solve(&g, v3(0, 1, 0), 0.0, cases[n].g, 3000, 1e-6);
        /* every column the beam crosses stops all of it but e^-tau */
        double source = 0.0, v = g.h[0] * g.h[1] * g.h[2];
        size_t count = (size_t)g.n[0] * g.n[1] * g.n[2];
        for (size_t c = 0; c < count; c++)
            source += g.q[c] * v;
        double area = (g.n[0] - 2 * CU_MSD_MARGIN) * g.h[0] * (g.n[2] - 2 * CU_MSD_MARGIN) * g.h[2];
        assert_true(fabs(source / (area * (1.0 - exp(-cases[n].tau))) - 1.0) < 1e-3);
        /* what leaves the centre column's base and top, a long way from the slab's edges: Marshak's outflow
         * (a phi + G.n) / (2a + 1), a = 2 D / h, the push G along the beam (down) */
        int ic = g.n[0] / 2, kc = g.n[2] / 2, j0 = (g.n[1] - cases[n].thick) / 2, j1 = j0 + cases[n].thick - 1;
        int cb = cu_msd_at(&g, ic, j0, kc), ct = cu_msd_at(&g, ic, j1, kc);
        double ab = 2.0 * g.d[cb] / g.h[1], at = 2.0 * g.d[ct] / g.h[1];
        double down = (ab * g.phi[cb] + g.push[cb]) / (2.0 * ab + 1.0);
        double up = (at * g.phi[ct] - g.push[ct]) / (2.0 * at + 1.0);
        double t = down + exp(-cases[n].tau), want = eddington_t(cases[n].tau, cases[n].g);
        print_message("slab tau %.0f g %.2f: T %.4f (Eddington %.4f), R %.4f, R + T %.4f, %d sweeps\n", cases[n].tau,
                      cases[n].g, t, want, up, up + t, g.sweeps);
        assert_true(fabs(t / want - 1.0) < 0.10);
        assert_true(fabs(up + t - 1.0) < 0.02); /* a conservative slab: reflected + transmitted = all of it */
        assert_true(g.change <= 1e-6);
        cu_msd_free(&g);
    }
}

/* A slanted sunbeam's first scattering takes exactly the light the slab stops: per unit of its area, the centre
 * column's cells hold mu0 (1 - e^-tau/mu0) of the beam's irradiance, the sun 30, 60 and 90 degrees high, through
 * cells of optical depth 0.17 to 10 (each cell 33 x 6.7 m: a layer's grid is wider than tall). Within 2 %; the beam
 * marched in half-cell steps from one point of each cell took 0.9 % to 87 % too little under the low sun and up to
 * 12 % too much under the high one. */
static void test_slanted_beam(void **st)
{
    (void)st;
    static const struct { double tau; int thick; } cases[] = {{2, 12}, {2, 4}, {5, 4}, {20, 12}, {40, 4}};
    double worst = 0.0;
    for (size_t n = 0; n < sizeof cases / sizeof cases[0]; n++)
        for (int e = 30; e <= 90; e += 30) {
            cu_msd g;
            slab(&g, cases[n].tau, cases[n].thick);
            double r = e * CU_PI / 180.0, mu0 = sin(r);
            cu_msd_solve(&g, v3(0.0, mu0, cos(r)), 0.0, 0.85, 1, 1e-5);
            double held = 0.0, want = mu0 * (1.0 - exp(-cases[n].tau / mu0));
            for (int j = 0; j < g.n[1]; j++)
                held += g.q[cu_msd_at(&g, g.n[0] / 2, j, g.n[2] / 2)] * g.h[1];
            worst = fmax(worst, fabs(held / want - 1.0));
            if (fabs(held / want - 1.0) > 0.02)
                print_message("tau %.0f in %d cells, sun %d degrees high: %.4f of the beam, want %.4f\n",
                              cases[n].tau, cases[n].thick, e, held, want);
            assert_true(fabs(held / want - 1.0) < 0.02);
            cu_msd_free(&g);
        }
    print_message("slanted beams: the first scattering within %.2f %% of the light each slab stops\n", 100.0 * worst);
}

/* An ellipsoid of radii r about (0, 1000, 0) m: core k_e 0.05 / m, boundary 40 m, no noise. */
static cu_cloud ellipsoid_cloud(vec3 r)
{
    cu_scene *s = calloc(1, sizeof *s);
    assert_non_null(s);
    cu_scene_defaults(s);
    s->noise = 0;
    cu_ellipsoid e = {{0, 1000, 0}, {r.x, r.y, r.z}};
    cu_cloud cl;
    double off[3] = {0, 0, 0};
    cu_cloud_build_ellipsoids(&cl, s, &e, 1, s->density_cm3, 40.0, off, NULL); /* copies what it needs of s */
    cl.ke = 0.05;
    cl.noise_on = 0;
    free(s);
    return cl;
}

/* A sphere of radius 300 m (ellipsoid_cloud), lit from +y. */
static void sphere(cu_msd *g, int cells)
{
    cu_cloud cl = ellipsoid_cloud(v3(300, 300, 300));
    cu_error err = {{0}};
    assert_int_equal(cu_msd_init(g, &cl, cells, &err), 0);
    cu_msd_sample(g, &cl);
}

static void test_sphere_symmetry_and_gradient(void **st)
{
    (void)st;
    cu_msd g;
    sphere(&g, 24);
    cu_msd_solve(&g, v3(0, 1, 0), 0.0, 0.85, 1000, 1e-7);
    assert_true(g.change <= 1e-7);
    int n = g.n[0], c = n / 2;
    assert_int_equal(g.n[0], g.n[2]);
    /* mirror symmetry about the sun's axis: x <-> -x and x <-> z */
    double worst = 0.0, most = 0.0;
    for (int k = 0; k < n; k++)
        for (int j = 0; j < g.n[1]; j++)
            for (int i = 0; i < n; i++) {
                double a = g.phi[cu_msd_at(&g, i, j, k)], b = g.phi[cu_msd_at(&g, n - 1 - i, j, k)];
                double t = g.phi[cu_msd_at(&g, k, j, i)];
                worst = fmax(worst, fmax(fabs(a - b), fabs(a - t)));
                most = fmax(most, a);
            }
    print_message("sphere: largest fluence %.3f, largest asymmetry %.2g\n", most, worst);
    assert_true(most > 0.1);
    assert_true(worst < 1e-3 * most); /* Gauss-Seidel's sweep order is the only asymmetry */
    /* the lit top holds more light than the base, and the flux on the axis runs down, away from the sun */
    int top = g.n[1] - CU_MSD_MARGIN - 2, base = CU_MSD_MARGIN + 1;
    double phi_top = g.phi[cu_msd_at(&g, c, top, c)], phi_base = g.phi[cu_msd_at(&g, c, base, c)];
    print_message("sphere: fluence near the top %.3f, near the base %.3f\n", phi_top, phi_base);
    assert_true(phi_top > 1.5 * phi_base);
    assert_true(phi_base > 0.0);
    assert_true(g.out[4 * cu_msd_at(&g, c, g.n[1] / 2, c) + 2] < 0.0f);
    cu_msd_free(&g);
}

/* A solve started from the last one (the sun moved half a degree) takes at most 70 % of the sweeps of one from nothing,
 * and finds the same light within 2 % (summed difference over summed fluence; the renderer's tolerance). The two are
 * not equal to the tolerance: the limiter's damped Picard rounds end where the coefficients stop moving the fluence,
 * which depends a little on where they started (1.5 % measured here, also at a ten times tighter tolerance). */
static void test_warm_start(void **st)
{
    (void)st;
    cu_msd g, fresh;
    sphere(&g, 24);
    sphere(&fresh, 24);
    double a = 0.5 * CU_PI / 180.0;
    vec3 moved = v3(sin(a), cos(a), 0);
    cu_msd_solve(&g, v3(0, 1, 0), 0.0, 0.85, 1000, 1e-5);
    cu_msd_solve(&g, moved, 0.0, 0.85, 1000, 1e-5);
    cu_msd_solve(&fresh, moved, 0.0, 0.85, 1000, 1e-5);
    size_t count = (size_t)g.n[0] * g.n[1] * g.n[2];
    double diff = 0.0, sum = 0.0;
    for (size_t c = 0; c < count; c++) {
        diff += fabs(g.phi[c] - fresh.phi[c]);
        sum += fresh.phi[c];
    }
    print_message("sweeps from nothing %d, after the sun moved half a degree %d; difference %.2g of the fluence\n",
                  fresh.sweeps, g.sweeps, diff / sum);
    assert_true(g.change <= 1e-5 && fresh.change <= 1e-5);
    assert_true(g.sweeps <= 0.7 * fresh.sweeps);
    assert_true(diff < 0.02 * sum);
    cu_msd_free(&g);
    cu_msd_free(&fresh);
}

/* A solve spread over frames (cu_msd_solve_begin, then cu_msd_solve_continue a few sweeps at a time) is the one-shot
 * solve bit for bit, from nothing and warm (the sun moved half a degree), whatever the slices; no call runs more
 * sweeps than it was given, and a slice shorter than the solve leaves it under way. */
static void test_solve_in_steps(void **st)
{
    (void)st;
    static const int slices[] = {1, 3, 17, 40, 41};
    double a = 0.5 * CU_PI / 180.0;
    vec3 suns[2] = {v3(0, 1, 0), v3(sin(a), cos(a), 0)};
    for (int n = 0; n < 5; n++) {
        cu_msd whole, g;
        sphere(&whole, 16);
        sphere(&g, 16);
        size_t count = (size_t)g.n[0] * g.n[1] * g.n[2];
        for (int s = 0; s < 2; s++) { /* from nothing, then warm */
            cu_msd_solve(&whole, suns[s], 0.73, 0.46, 1000, 1e-5);
            cu_msd_solve_begin(&g, suns[s], 0.73, 0.46, 1000, 1e-5);
            int calls = 0, total = 0;
            while (g.solving) {
                int ran = cu_msd_solve_continue(&g, slices[n]);
                assert_true(ran >= 1 && ran <= slices[n]);
                total += ran;
                calls++;
            }
            if (n == 0)
                print_message("in steps: %d sweeps %s\n", g.sweeps, s ? "after the sun moved" : "from nothing");
            assert_int_equal(total, g.sweeps);
            assert_int_equal(g.sweeps, whole.sweeps);
            assert_int_equal(calls, (g.sweeps + slices[n] - 1) / slices[n]); /* a slice short of the end ran whole */
            assert_memory_equal(g.phi, whole.phi, count * sizeof *g.phi);
            assert_memory_equal(g.out, whole.out, 4 * count * sizeof *g.out);
        }
        cu_msd_free(&g);
        cu_msd_free(&whole);
    }
}

/* The density sampled a few slices at a time (a renderer's frames) is the density sampled at once. */
static void test_sample_in_slices(void **st)
{
    (void)st;
    cu_msd whole, g;
    sphere(&whole, 16);
    sphere(&g, 16);
    size_t count = (size_t)g.n[0] * g.n[1] * g.n[2];
    cu_cloud cl = ellipsoid_cloud(v3(300, 200, 250)); /* another look, in the same grid */
    cu_msd_sample(&whole, &cl);
    for (int k = 0; k < g.n[2]; k += 3)
        cu_msd_sample_slices(&g, &cl, k, k + 3);
    assert_memory_equal(g.ke, whole.ke, count * sizeof *g.ke);
    double sum = 0.0;
    for (size_t c = 0; c < count; c++)
        sum += g.ke[c];
    assert_true(sum > 0.0);
    cu_msd_free(&g);
    cu_msd_free(&whole);
}

/* A fine grid's first solve starts from a coarse grid's answer (ms_diffusion.c start_from_coarse): a sphere of 96
 * cells a side settles within the renderer's budget of 1000 sweeps (from nothing it stopped at 1000, short of the
 * tolerance), and its light is the light of a solve that started from it and ran twice as long again. */
static void test_fine_grid_converges(void **st)
{
    (void)st;
    cu_msd g;
    sphere(&g, 96);
    cu_msd_solve(&g, v3(0, 1, 0), 0.73, 0.46, 1000, 1e-5);
    print_message("96 cells: %d sweeps, last change %.2g\n", g.sweeps, g.change);
    assert_true(g.change <= 1e-5 && g.sweeps < 1000);
    size_t count = (size_t)g.n[0] * g.n[1] * g.n[2];
    float *first = malloc(count * sizeof *first);
    assert_non_null(first);
    memcpy(first, g.phi, count * sizeof *first);
    cu_msd_solve(&g, v3(0, 1, 0), 0.73, 0.46, 2000, 1e-7);
    double diff = 0.0, sum = 0.0;
    for (size_t c = 0; c < count; c++) {
        diff += fabs(g.phi[c] - first[c]);
        sum += g.phi[c];
    }
    print_message("96 cells: %d more sweeps to a change of %.2g moved the fluence by %.2g of it\n", g.sweeps, g.change,
                  diff / sum);
    assert_true(diff < 0.02 * sum);
    free(first);
    cu_msd_free(&g);
}

/* A grid of 40^3 cubic 10 m cells, filled directly: k_e 0.05 where inside(i, j, k) says, else empty. */
static void cube_grid(cu_msd *g, int (*inside)(int, int, int))
{
    empty_grid(g, v3(-180, -180, -180), v3(180, 180, 180), 40);
    assert_true(g->n[0] == 40 && g->n[1] == 40 && g->n[2] == 40 && fabs(g->h[0] - 10.0) < 1e-9);
    for (int k = 0; k < 40; k++)
        for (int j = 0; j < 40; j++)
            for (int i = 0; i < 40; i++)
                g->ke[cu_msd_at(g, i, j, k)] = inside(i, j, k) ? 0.05f : 0.0f;
    cu_msd_solve(g, v3(0, 1, 0), 0.0, 0.85, 1, 1e-5); /* the weights come with the solve */
}

static int level(int i, int j, int k) { (void)i; (void)k; return j < 20; }
static int slant2(int i, int j, int k) { (void)k; return i + j < 40; }
static int slant3(int i, int j, int k) { return i + j + k < 60; }
static int ball(int i, int j, int k)
{
    return (i - 19.5) * (i - 19.5) + (j - 19.5) * (j - 19.5) + (k - 19.5) * (k - 19.5) < 144.0;
}

/* Faces of cloud cell (i, j, k) to empty space. */
static int open_faces(const cu_msd *g, int i, int j, int k)
{
    static const int o[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    int n = 0;
    for (int f = 0; f < 6; f++) {
        int a = i + o[f][0], b = j + o[f][1], c = k + o[f][2];
        n += a < 0 || b < 0 || c < 0 || a >= g->n[0] || b >= g->n[1] || c >= g->n[2] ||
             g->ke[cu_msd_at(g, a, b, c)] == 0.0f;
    }
    return n;
}

/* The light leaves through the cloud's true surface, not the staircase of cell faces that stands for it: a plane
 * slanted as (1, 1, 0) or (1, 1, 1) is covered by sqrt 2 or sqrt 3 times its area of faces, so each of its surface
 * cells' faces leaks 1 / sqrt 2 or 1 / sqrt 3 (exactly: the Sobel operator's gradient of a symmetric staircase is
 * symmetric); a level one 1. Over a sphere of radius 12 cells the faces cover about 1.5 times its area; weighted,
 * they cover its area. */
static void test_leak_weights(void **st)
{
    (void)st;
    static const struct { int (*inside)(int, int, int); double want; } planes[] = {
        {level, 1.0}, {slant2, 0.70710678}, {slant3, 0.57735027}};
    for (size_t p = 0; p < sizeof planes / sizeof planes[0]; p++) {
        cu_msd g;
        cube_grid(&g, planes[p].inside);
        int checked = 0;
        for (int k = 2; k < 38; k++)
            for (int j = 2; j < 38; j++)
                for (int i = 2; i < 38; i++)
                    if (g.ke[cu_msd_at(&g, i, j, k)] > 0.0f && open_faces(&g, i, j, k) > 0) {
                        assert_true(fabs(g.leak[cu_msd_at(&g, i, j, k)] - planes[p].want) < 1e-6);
                        checked++;
                    }
        print_message("plane %zu: %d surface cells leak %.4f a face\n", p, checked, planes[p].want);
        assert_true(checked > 500);
        cu_msd_free(&g);
    }
    cu_msd g;
    cube_grid(&g, ball);
    double faces = 0.0, weighted = 0.0, area = 4.0 * CU_PI * 120.0 * 120.0;
    for (int k = 0; k < 40; k++)
        for (int j = 0; j < 40; j++)
            for (int i = 0; i < 40; i++)
                if (g.ke[cu_msd_at(&g, i, j, k)] > 0.0f) {
                    int n = open_faces(&g, i, j, k);
                    faces += n * 100.0;
                    weighted += n * 100.0 * g.leak[cu_msd_at(&g, i, j, k)];
                }
    print_message("sphere of 120 m: faces to empty space %.3f of its area, weighted %.3f\n", faces / area,
                  weighted / area);
    assert_true(faces > 1.3 * area);
    assert_true(fabs(weighted / area - 1.0) < 0.05);
    cu_msd_free(&g);
}

/* A flat layer's grid has cells wider than tall (a quarter of the cells across its thickness): here 27.8 m across and
 * 4.4 m tall. A staircase one cell up per cell across is a slope of 4.4 in 27.8 there, not 45 degrees: its faces cover
 * |n_x| + |n_y| = 1.145 times its area (n its unit normal in metres), so each leaks 0.873, not the cubic grid's
 * 1 / sqrt 2; a level surface leaks 1. */
static int flat_level(int i, int j, int k) { (void)i; (void)k; return j >= 2 && j < 8; }
static int flat_slant(int i, int j, int k) { (void)k; return j >= 2 && i + j < 24; }

static void test_leak_weights_flat(void **st)
{
    (void)st;
    int (*const shapes[2])(int, int, int) = {flat_level, flat_slant};
    for (int p = 0; p < 2; p++) {
        cu_msd g;
        empty_grid(&g, v3(-500, -20, -500), v3(500, 20, 500), 40);
        assert_true(g.n[0] == 40 && g.n[1] == 13 && g.h[0] > 5.0 * g.h[1]);
        for (int k = 0; k < g.n[2]; k++)
            for (int j = 0; j < g.n[1]; j++)
                for (int i = 0; i < g.n[0]; i++)
                    g.ke[cu_msd_at(&g, i, j, k)] = shapes[p](i, j, k) ? 0.5f : 0.0f;
        cu_msd_solve(&g, v3(0, 1, 0), 0.0, 0.85, 1, 1e-5);
        double nx = p ? 1.0 / g.h[0] : 0.0, ny = 1.0 / g.h[1], want = sqrt(nx * nx + ny * ny) / (nx + ny);
        int checked = 0;
        /* the slant's cells on its top side, away from its ends and the grid's edges */
        for (int k = 2; k < g.n[2] - 2; k++)
            for (int j = 3; j < 8; j++)
                for (int i = 4; i < 21; i++)
                    if (shapes[p](i, j, k) && !shapes[p](i + 1, j, k) + !shapes[p](i, j + 1, k) > 0) {
                        assert_true(fabs(g.leak[cu_msd_at(&g, i, j, k)] - want) < 1e-6);
                        checked++;
                    }
        print_message("flat grid (cells %.1f x %.1f m), %s: %d surface cells leak %.4f a face\n", g.h[0], g.h[1],
                      p ? "slant" : "level", checked, want);
        assert_true(checked > 100);
        if (p)
            assert_true(want > 0.85 && want < 0.9);
        cu_msd_free(&g);
    }
}

static void all_finite(const cu_msd *g)
{
    size_t count = (size_t)g->n[0] * g->n[1] * g->n[2];
    for (size_t c = 0; c < count; c++) {
        assert_true(isfinite(g->q[c]) && g->q[c] >= 0.0f);
        assert_true(isfinite(g->phi[c]) && g->phi[c] >= 0.0f);
        for (int e = 0; e < 4; e++)
            assert_true(isfinite(g->out[4 * c + e]));
    }
}

static void test_extremes(void **st)
{
    (void)st;
    cu_error e = {{0}};
    cu_msd g;
    cu_cloud empty;
    memset(&empty, 0, sizeof empty);
    /* grids out of range are refused, by name */
    assert_int_equal(cu_msd_init(&g, &empty, CU_MSD_MIN_CELLS - 1, &e), 1);
    assert_non_null(strstr(e.msg, "ms.grid"));
    assert_int_equal(cu_msd_init(&g, &empty, CU_MSD_MAX_CELLS + 1, &e), 1);
    /* an empty cloud (zero bounds): a grid of nothing, solved to nothing */
    assert_int_equal(cu_msd_init(&g, &empty, 16, &e), 0);
    cu_msd_solve(&g, v3(0, 1, 0), 0.0, 0.85, 50, 1e-5);
    all_finite(&g);
    assert_true(g.phi[cu_msd_at(&g, g.n[0] / 2, g.n[1] / 2, g.n[2] / 2)] == 0.0f);
    cu_msd_free(&g);
    /* optical depth per cell from a wisp to 1e5, asymmetry -0.9 to 0.99, a chopped peak of 0.9, bad inputs, the sun
     * along an axis, a diagonal and grazing */
    static const double ke[] = {1e-6, 1e-3, 0.05, 1.0, 1e3};
    static const double asym[] = {-0.9, 0.0, 0.85, 0.99, NAN};
    static const double f[] = {0.0, 0.5, 0.9, -1.0};
    vec3 suns[] = {v3(0, 1, 0), v3(0.57735, 0.57735, 0.57735), v3(0.99995, 0.01, 0), v3(0, -1, 0)};
    for (size_t a = 0; a < sizeof ke / sizeof ke[0]; a++) {
        sphere(&g, 12);
        size_t count = (size_t)g.n[0] * g.n[1] * g.n[2];
        for (size_t c = 0; c < count; c++)
            g.ke[c] = (float)(g.ke[c] / 0.05 * ke[a]);
        for (size_t b = 0; b < sizeof asym / sizeof asym[0]; b++)
            for (size_t h = 0; h < sizeof f / sizeof f[0]; h++) {
                cu_msd_solve(&g, suns[(a + b + h) % 4], f[h], asym[b], 60, 1e-5);
                all_finite(&g);
            }
        cu_msd_free(&g);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_slab_energy_and_transmission),
        cmocka_unit_test(test_slanted_beam),
        cmocka_unit_test(test_sphere_symmetry_and_gradient),
        cmocka_unit_test(test_warm_start),
        cmocka_unit_test(test_solve_in_steps),
        cmocka_unit_test(test_sample_in_slices),
        cmocka_unit_test(test_fine_grid_converges),
        cmocka_unit_test(test_leak_weights),
        cmocka_unit_test(test_leak_weights_flat),
        cmocka_unit_test(test_extremes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
