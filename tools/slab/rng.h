/* Seeded reproducible RNG for the slab Monte Carlo: xoshiro256** seeded by splitmix64, jump() for independent streams. */
#ifndef CU_SLAB_RNG_H
#define CU_SLAB_RNG_H
#include <stdint.h>

typedef struct { uint64_t s[4]; } cu_rng;

static inline uint64_t cu_rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

/* splitmix64 expands one 64-bit seed into a well-mixed 256-bit state (the seeding Vigna recommends). */
static inline void cu_rng_seed(cu_rng *r, uint64_t seed)
{
    for (int i = 0; i < 4; i++) {
        uint64_t z = (seed += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        r->s[i] = z ^ (z >> 31);
    }
}

static inline uint64_t cu_rng_next(cu_rng *r)
{
    uint64_t *s = r->s;
    uint64_t result = cu_rotl(s[1] * 5, 7) * 9;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0]; s[3] ^= s[1]; s[1] ^= s[2]; s[0] ^= s[3];
    s[2] ^= t;
    s[3] = cu_rotl(s[3], 45);
    return result;
}

/* Uniform in [0,1) with 53 random bits. */
static inline double cu_rng_u01(cu_rng *r) { return (double)(cu_rng_next(r) >> 11) * 0x1.0p-53; }
/* Uniform in (0,1]: safe argument for log() when sampling free paths. */
static inline double cu_rng_u01_open0(cu_rng *r) { return ((double)(cu_rng_next(r) >> 11) + 1.0) * 0x1.0p-53; }

/* Advances the stream by 2^128 draws: non-overlapping substreams, one per batch/thread/rank. */
static inline void cu_rng_jump(cu_rng *r)
{
    static const uint64_t J[] = { 0x180ec6d33cfd0abaULL, 0xd5a61266f0c9392cULL,
                                  0xa9582618e03fc9aaULL, 0x39abdc4529b1661cULL };
    uint64_t s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    for (int i = 0; i < 4; i++)
        for (int b = 0; b < 64; b++) {
            if (J[i] & ((uint64_t)1 << b)) { s0 ^= r->s[0]; s1 ^= r->s[1]; s2 ^= r->s[2]; s3 ^= r->s[3]; }
            cu_rng_next(r);
        }
    r->s[0] = s0; r->s[1] = s1; r->s[2] = s2; r->s[3] = s3;
}
#endif
