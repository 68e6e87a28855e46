/* src/core/noise.h: the 64^3 tileable noise texture (fixed seed, integer hash), its mip chain, and the CPU twin of the
 * shader's fractal noise (Kol eq. 3.74) so tests and the path tracer see exactly the texel values the GPU sees. */
#ifndef CU_NOISE_H
#define CU_NOISE_H
#include <stdint.h>

#define CU_NOISE_SIZE 64
#define CU_NOISE_LEVELS 7 /* 64, 32, 16, 8, 4, 2, 1 */
#define CU_NOISE_OCTAVES 5

typedef struct cu_noise {
    uint8_t *level[CU_NOISE_LEVELS]; /* level L is (64>>L)^3 bytes, x fastest */
    double level_mean[CU_NOISE_LEVELS];
    double level_std[CU_NOISE_LEVELS];
} cu_noise;

/* Kol eq. 3.74 weights for LOD 0..4. */
extern const double cu_noise_weights[CU_NOISE_OCTAVES];

int cu_noise_create(cu_noise *n, uint32_t seed);
void cu_noise_destroy(cu_noise *n);
/* Trilinear sample of one level with repeat wrap at texture coordinates (1 = one tile), in [0,1]. */
double cu_noise_sample(const cu_noise *n, int level, double u, double v, double w);
/* Fractal noise in [-1,1] at texture coordinates p (Kol eq. 3.74: LODs 0..4 at p and at 8p, each sum minus 0.75,
 * clamped to [0,1], mapped to [-1,1]). octaves < 5 drops the finest levels, replacing each by its mean. */
double cu_noise_fractal(const cu_noise *n, const double p[3], int octaves);
/* The octaves baked into one 64^3 grid (x fastest, texel centres as GL's): out[i] = the sum over levels L of
 * weight_L x (level L trilinear at the centre of level-0 texel i), levels dropped by `octaves` < 5 as their mean.
 * Sampled trilinearly at p and 8p, summed, minus 1.5 and clamped, it stands in for cu_noise_fractal (2 reads, not 10):
 * exact at level 0, an interpolation of the coarser levels' trilinear functions between texel centres. */
void cu_noise_bake(const cu_noise *n, int octaves, float *out);
/* The CPU twin of the baked fractal noise (density.glsl's NOISE_BAKED) at texture coordinates p, in [-1, 1]. */
double cu_noise_fractal_baked(const float *baked, const double p[3]);
/* The integer hash used for the lattice gradients (lowbias32); exposed for tests. */
uint32_t cu_noise_hash(uint32_t x);
#endif
