/* The CPU's default sampler (core/sampler.c, IL_SAMPLER_SOBOL) in a
 * device-safe header: the same numbers, bit for bit, for the same (seed,
 * pixel, sample index, dimension), so the GPU draws what the CPU path
 * tracer draws.  Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT
 * 9(4)): dimensions in pairs, each pair the (0,2)-sequence of Sobol
 * dimensions 0 and 1, nested uniform Owen scrambling by the Laine-Karras
 * style hash, and the sample index shuffled (Owen-scrambled) per pair.  A
 * 1D draw takes the first member of a fresh pair. */
#ifndef IL_KERNEL_SOBOL_H
#define IL_KERNEL_SOBOL_H

#include "kernel/kernel_compat.h"

typedef struct ilk_sobol {
    uint64_t key;              /* hash(seed, pixel) */
    uint32_t index_reversed;   /* the sample index, bit-reversed */
    uint32_t dim;              /* next dimension */
} ilk_sobol;

/* Reverses the 32 bits of x (on the CPU: a byte swap, then nibbles, pairs,
 * bits). */
IL_DEVICE_INLINE uint32_t ilk_reverse_bits(uint32_t x)
{
#if defined(__CUDA_ARCH__)
    return __brev(x);
#else
#if defined(__GNUC__)
    x = __builtin_bswap32(x);
#else
    x = ((x & 0x0000ffffu) << 16) | ((x & 0xffff0000u) >> 16);
    x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
#endif
    x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
    x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
    x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
    return x;
#endif
}

/* core/rng.h's il_hash64 and il_hash_combine (ilk_path_sample's pcg
 * streams use another finaliser, kernel_path.h's ilk_hash64). */
IL_DEVICE_INLINE uint64_t ilk_mix64(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}

IL_DEVICE_INLINE uint64_t ilk_hash_combine(uint64_t a, uint64_t b)
{
    return ilk_mix64(a ^ (b + 0x9e3779b97f4a7c15ULL + (a << 6) + (a >> 2)));
}

/* Second Sobol dimension, bit-reversed.  With the polynomial x + 1 (degree 1,
 * m_1 = 1) the direction numbers follow v_k = v_{k-1} ^ (v_{k-1} >> 1),
 * v_0 = 2^31 (Bratley & Fox 1988; Joe & Kuo 2008): the rows of Pascal's
 * triangle mod 2, so output bit j (counted from the top) is the XOR of the
 * index bits k with C(k, j) odd, i.e. (Lucas' theorem) with j a bit-subset of
 * k.  That "superset XOR" transform takes five shift-and-mask steps, one per
 * bit of j, and yields the result bit-reversed (bit j at position j). */
IL_DEVICE_INLINE uint32_t ilk_sobol_dim1_reversed(uint32_t index)
{
    index ^= (index >> 1) & 0x55555555u;
    index ^= (index >> 2) & 0x33333333u;
    index ^= (index >> 4) & 0x0f0f0f0fu;
    index ^= (index >> 8) & 0x00ff00ffu;
    index ^= (index >> 16) & 0x0000ffffu;
    return index;
}

/* Burley 2020, section 3 (improved Laine-Karras permutation): a hash in which
 * every output bit depends only on the same and lower input bits, so applied
 * to a bit-reversed value it is a nested uniform Owen scramble. */
IL_DEVICE_INLINE uint32_t ilk_laine_karras(uint32_t x, uint32_t seed)
{
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

IL_DEVICE_INLINE float ilk_u32_to_float(uint32_t x) { return (float)(x >> 8) * (1.0f / 16777216.0f); }

IL_DEVICE_INLINE ilk_sobol ilk_sobol_start(uint64_t seed, uint64_t pixel, uint32_t sample_index)
{
    ilk_sobol s;
    s.key = ilk_hash_combine(ilk_mix64(seed), pixel);
    s.index_reversed = ilk_reverse_bits(sample_index);
    s.dim = 0;
    return s;
}

/* The seeds of the pair (dim, dim+1): x, y scramble the two members,
 * shuffle the index. */
IL_DEVICE_INLINE void ilk_sobol_pair_seeds(const ilk_sobol *s, uint32_t dim, uint32_t *x, uint32_t *y,
                                           uint32_t *shuffle)
{
    uint64_t key = ilk_mix64(s->key + 0x9e3779b97f4a7c15ULL * (uint64_t)(dim + 1));
    *x = (uint32_t)key;
    *y = (uint32_t)(key >> 32);
    *shuffle = (uint32_t)((key * 0xda942042e4dd58b5ULL) >> 32);
}

IL_DEVICE_INLINE void ilk_sobol_2d(ilk_sobol *s, float *u, float *v)
{
    uint32_t kx, ky, ks;
    ilk_sobol_pair_seeds(s, s->dim, &kx, &ky, &ks);
    s->dim += 2;
    uint32_t i = ilk_reverse_bits(ilk_laine_karras(s->index_reversed, ks));
    *u = ilk_u32_to_float(ilk_reverse_bits(ilk_laine_karras(i, kx)));
    *v = ilk_u32_to_float(ilk_reverse_bits(ilk_laine_karras(ilk_sobol_dim1_reversed(i), ky)));
}

IL_DEVICE_INLINE float ilk_sobol_1d(ilk_sobol *s)
{
    uint32_t kx, ky, ks;
    ilk_sobol_pair_seeds(s, s->dim, &kx, &ky, &ks);
    s->dim += 2;
    uint32_t i = ilk_reverse_bits(ilk_laine_karras(s->index_reversed, ks));
    return ilk_u32_to_float(ilk_reverse_bits(ilk_laine_karras(i, kx)));
}

#endif
