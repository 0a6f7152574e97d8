/* Random numbers: hashing for keyed streams and the PCG32 generator
 * (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically
 * Good Algorithms for Random Number Generation", pcg32 XSH-RR). */
#ifndef IL_CORE_RNG_H
#define IL_CORE_RNG_H

#include <stdint.h>

/* 64-bit finaliser of MurmurHash3 / SplitMix64: a good integer mixer. */
static inline uint64_t il_hash64(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    return x;
}

static inline uint64_t il_hash_combine(uint64_t a, uint64_t b)
{
    return il_hash64(a ^ (b + 0x9e3779b97f4a7c15ull + (a << 6) + (a >> 2)));
}

typedef struct il_pcg32 { uint64_t state, inc; } il_pcg32;

static inline uint32_t il_pcg32_next(il_pcg32 *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ull + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
}

/* A generator whose stream depends only on (seed, stream). */
static inline il_pcg32 il_pcg32_seed(uint64_t seed, uint64_t stream)
{
    il_pcg32 r;
    r.state = 0u;
    r.inc = (stream << 1u) | 1u;
    il_pcg32_next(&r);
    r.state += seed;
    il_pcg32_next(&r);
    return r;
}

/* Uniform float in [0, 1): the top 24 bits. */
static inline float il_u32_to_float(uint32_t x) { return (float)(x >> 8) * 0x1p-24f; }
static inline float il_pcg32_float(il_pcg32 *r) { return il_u32_to_float(il_pcg32_next(r)); }

#endif
