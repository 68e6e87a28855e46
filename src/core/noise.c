/* src/core/noise.c: builds the tileable 64^3 noise texture from an integer hash (identical on every CPU: no sin-hash,
 * no libm in the lattice), box-filters its mip chain on the CPU (so GPU and CPU use the same bytes), and samples it. */
#include "noise.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

const double cu_noise_weights[CU_NOISE_OCTAVES] = {0.015, 0.035, 0.1, 0.35, 1.5};

uint32_t cu_noise_hash(uint32_t x)
{
    /* lowbias32 (Chris Wellons): good avalanche, integer-only, so the texture is bit-identical everywhere. */
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

static const int grad12[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1},
                                  {1, 0, -1}, {-1, 0, -1}, {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};

static double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

/* Periodic Perlin gradient noise with `period` lattice cells per tile; p in lattice units. */
static double perlin_periodic(double x, double y, double z, int period, uint32_t seed)
{
    int xi = (int)floor(x), yi = (int)floor(y), zi = (int)floor(z);
    double fx = x - xi, fy = y - yi, fz = z - zi;
    double acc[2][2][2];
    for (int dz = 0; dz < 2; dz++)
        for (int dy = 0; dy < 2; dy++)
            for (int dx = 0; dx < 2; dx++) {
                uint32_t X = (uint32_t)(((xi + dx) % period + period) % period);
                uint32_t Y = (uint32_t)(((yi + dy) % period + period) % period);
                uint32_t Z = (uint32_t)(((zi + dz) % period + period) % period);
                uint32_t h = cu_noise_hash(X + cu_noise_hash(Y + cu_noise_hash(Z + cu_noise_hash(seed))));
                const int *g = grad12[h % 12];
                acc[dz][dy][dx] = g[0] * (fx - dx) + g[1] * (fy - dy) + g[2] * (fz - dz);
            }
    double u = fade(fx), v = fade(fy), w = fade(fz);
    double x00 = acc[0][0][0] + u * (acc[0][0][1] - acc[0][0][0]);
    double x10 = acc[0][1][0] + u * (acc[0][1][1] - acc[0][1][0]);
    double x01 = acc[1][0][0] + u * (acc[1][0][1] - acc[1][0][0]);
    double x11 = acc[1][1][0] + u * (acc[1][1][1] - acc[1][1][0]);
    double y0 = x00 + v * (x10 - x00), y1 = x01 + v * (x11 - x01);
    return y0 + w * (y1 - y0);
}

static void level_stats(const uint8_t *d, int n, double *mean, double *sd)
{
    double s = 0, s2 = 0;
    long cnt = (long)n * n * n;
    for (long i = 0; i < cnt; i++) {
        s += d[i];
        s2 += (double)d[i] * d[i];
    }
    double m = s / cnt;
    *mean = m / 255.0;
    double var = s2 / cnt - m * m;
    *sd = sqrt(var > 0 ? var : 0) / 255.0;
}

int cu_noise_create(cu_noise *n, uint32_t seed)
{
    memset(n, 0, sizeof *n);
    const int N = CU_NOISE_SIZE;
    double *f = malloc(sizeof(double) * N * N * N);
    if (!f)
        return 1;
    /* Octaves with 2..32 lattice cells per tile. Low frequencies dominate so that the coarse mip levels, which carry
     * the large weights of eq. 3.74 (1.5 at LOD 4), keep real variation instead of averaging to grey. */
    static const int periods[] = {2, 4, 8, 16, 32};
    static const double amps[] = {1.0, 0.5, 0.25, 0.125, 0.0625};
    double lo = 1e30, hi = -1e30;
    for (int z = 0; z < N; z++)
        for (int y = 0; y < N; y++)
            for (int x = 0; x < N; x++) {
                double v = 0;
                for (int o = 0; o < 5; o++) {
                    double sc = (double)periods[o] / N;
                    v += amps[o] * perlin_periodic((x + 0.5) * sc, (y + 0.5) * sc, (z + 0.5) * sc, periods[o],
                                                   seed * 7919u + (uint32_t)o);
                }
                f[(z * N + y) * N + x] = v;
                if (v < lo) lo = v;
                if (v > hi) hi = v;
            }
    for (int L = 0; L < CU_NOISE_LEVELS; L++) {
        int s = N >> L;
        n->level[L] = malloc((size_t)s * s * s);
        if (!n->level[L]) {
            free(f);
            cu_noise_destroy(n);
            return 1;
        }
    }
    for (long i = 0; i < (long)N * N * N; i++) {
        double t = (f[i] - lo) / (hi - lo);
        n->level[0][i] = (uint8_t)lround(t * 255.0);
    }
    free(f);
    /* Box-filtered mip chain with rounding: what glGenerateMipmap would do, but defined, so the CPU twin is exact. */
    for (int L = 1; L < CU_NOISE_LEVELS; L++) {
        int s = N >> L, ps = s * 2;
        const uint8_t *src = n->level[L - 1];
        uint8_t *dst = n->level[L];
        for (int z = 0; z < s; z++)
            for (int y = 0; y < s; y++)
                for (int x = 0; x < s; x++) {
                    unsigned sum = 0;
                    for (int k = 0; k < 8; k++)
                        sum += src[((2 * z + (k >> 2)) * ps + 2 * y + ((k >> 1) & 1)) * ps + 2 * x + (k & 1)];
                    dst[(z * s + y) * s + x] = (uint8_t)((sum + 4) / 8);
                }
    }
    for (int L = 0; L < CU_NOISE_LEVELS; L++)
        level_stats(n->level[L], N >> L, &n->level_mean[L], &n->level_std[L]);
    return 0;
}

void cu_noise_destroy(cu_noise *n)
{
    for (int L = 0; L < CU_NOISE_LEVELS; L++) {
        free(n->level[L]);
        n->level[L] = NULL;
    }
}

static int wrap(int i, int n) { return ((i % n) + n) % n; }

/* Texel (x, y, z) of an s^3 grid, x fastest: bytes (the noise's levels) or floats (the baked grid). */
static double texel(const void *d, int is_float, int s, int x, int y, int z)
{
    size_t i = ((size_t)z * s + y) * s + x;
    return is_float ? (double)((const float *)d)[i] : (double)((const uint8_t *)d)[i];
}

/* GL_LINEAR with GL_REPEAT on an s^3 grid at texture coordinates (u, v, w): texel centres at (i + 0.5) / s. */
static double trilinear(const void *d, int is_float, int s, double u, double v, double w)
{
    double x = u * s - 0.5, y = v * s - 0.5, z = w * s - 0.5;
    double fx0 = floor(x), fy0 = floor(y), fz0 = floor(z);
    double fx = x - fx0, fy = y - fy0, fz = z - fz0;
    int x0 = wrap((int)fmod(fx0, s), s), y0 = wrap((int)fmod(fy0, s), s), z0 = wrap((int)fmod(fz0, s), s);
    int x1 = (x0 + 1) % s, y1 = (y0 + 1) % s, z1 = (z0 + 1) % s;
#define T(X, Y, Z) texel(d, is_float, s, X, Y, Z)
    double c00 = T(x0, y0, z0) + fx * (T(x1, y0, z0) - T(x0, y0, z0));
    double c10 = T(x0, y1, z0) + fx * (T(x1, y1, z0) - T(x0, y1, z0));
    double c01 = T(x0, y0, z1) + fx * (T(x1, y0, z1) - T(x0, y0, z1));
    double c11 = T(x0, y1, z1) + fx * (T(x1, y1, z1) - T(x0, y1, z1));
#undef T
    double c0 = c00 + fy * (c10 - c00), c1 = c01 + fy * (c11 - c01);
    return c0 + fz * (c1 - c0);
}

double cu_noise_sample(const cu_noise *n, int level, double u, double v, double w)
{
    return trilinear(n->level[level], 0, CU_NOISE_SIZE >> level, u, v, w) / 255.0;
}

double cu_noise_fractal(const cu_noise *n, const double p[3], int octaves)
{
    if (octaves < 1) octaves = 1;
    if (octaves > CU_NOISE_OCTAVES) octaves = CU_NOISE_OCTAVES;
    double total = 0;
    for (int layer = 0; layer < 2; layer++) {
        double sc = layer ? 8.0 : 1.0, sum = 0;
        for (int L = 0; L < CU_NOISE_OCTAVES; L++) {
            double v = L >= CU_NOISE_OCTAVES - octaves ? cu_noise_sample(n, L, p[0] * sc, p[1] * sc, p[2] * sc)
                                                       : n->level_mean[L];
            sum += cu_noise_weights[L] * v;
        }
        total += sum - 0.75;
    }
    if (total < 0) total = 0;
    if (total > 1) total = 1;
    return total * 2.0 - 1.0;
}

void cu_noise_bake(const cu_noise *n, int octaves, float *out)
{
    if (octaves < 1) octaves = 1;
    if (octaves > CU_NOISE_OCTAVES) octaves = CU_NOISE_OCTAVES;
    const int s = CU_NOISE_SIZE;
    double dropped = 0; /* the levels switched off, at their mean (as cu_noise_fractal) */
    for (int L = 0; L < CU_NOISE_OCTAVES - octaves; L++)
        dropped += cu_noise_weights[L] * n->level_mean[L];
    for (int z = 0; z < s; z++)
        for (int y = 0; y < s; y++)
            for (int x = 0; x < s; x++) {
                double u = (x + 0.5) / s, v = (y + 0.5) / s, w = (z + 0.5) / s, sum = dropped;
                for (int L = CU_NOISE_OCTAVES - octaves; L < CU_NOISE_OCTAVES; L++)
                    sum += cu_noise_weights[L] * cu_noise_sample(n, L, u, v, w);
                out[((size_t)z * s + y) * s + x] = (float)sum;
            }
}

double cu_noise_fractal_baked(const float *baked, const double p[3])
{
    const int n = CU_NOISE_SIZE;
    double total = trilinear(baked, 1, n, p[0], p[1], p[2]) + trilinear(baked, 1, n, 8 * p[0], 8 * p[1], 8 * p[2]) - 1.5;
    if (total < 0) total = 0;
    if (total > 1) total = 1;
    return total * 2.0 - 1.0;
}
