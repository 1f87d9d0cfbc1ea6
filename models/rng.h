/* rng.h — small seeded pseudo-random generator (splitmix64) for resampling.
 *
 * Every random choice in models/ (bootstrap resamples, cross-validation
 * folds) goes through an explicit rng_state seeded by the caller, so results
 * are reproducible and there is no hidden global state.
 */
#ifndef MODELS_RNG_H
#define MODELS_RNG_H

#include <stddef.h>
#include <stdint.h>

typedef struct rng_state { uint64_t s; } rng_state;

static inline rng_state rng_seed(uint64_t seed)
{
    rng_state r = { seed ^ 0x9e3779b97f4a7c15ULL };
    return r;
}

static inline uint64_t rng_next(rng_state *r)
{
    uint64_t z = (r->s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/* Uniform integer in [0, n); n > 0.  The modulo bias (< n / 2^64) is
 * irrelevant for sample sizes used here. */
static inline size_t rng_below(rng_state *r, size_t n)
{
    return (size_t)(rng_next(r) % (uint64_t)n);
}

/* Uniform double in [0, 1). */
static inline double rng_uniform(rng_state *r)
{
    return (double)(rng_next(r) >> 11) * 0x1.0p-53;
}

#endif
