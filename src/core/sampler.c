/* Per-pixel sample streams; see sampler.h.
 *
 * Sobol: Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4).
 * Dimensions come in pairs; each pair is the (0,2)-sequence formed by the
 * first two Sobol dimensions (dimension 0 is the van der Corput sequence, the
 * bit-reversed index; dimension 1 uses the direction numbers of the primitive
 * polynomial x + 1).  Every pair gets its own nested uniform Owen scrambling
 * (Laine-Karras style hash, Burley section 3) and its own shuffle of the
 * sample index (the index itself Owen-scrambled with another seed, Burley
 * section 4), so pairs are decorrelated from each other ("padding").
 *
 * PCG: il_pcg32 seeded from hash(seed, pixel, index), one number per draw. */
#include "core/sampler.h"

/* Reverses the 32 bits of x (a byte swap, then nibbles, pairs, bits). */
static inline uint32_t reverse_bits(uint32_t x)
{
    x = __builtin_bswap32(x);
    x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
    x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
    x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
    return x;
}

/* Reverses the bits of both 32-bit halves of x at once (the same steps on
 * 64 bits; the byte swap also swaps the halves, which the caller undoes by
 * reading them the other way round). */
static inline uint64_t reverse_bits_pair_swapped(uint64_t x)
{
    x = __builtin_bswap64(x);
    x = ((x & 0x0f0f0f0f0f0f0f0full) << 4) | ((x & 0xf0f0f0f0f0f0f0f0ull) >> 4);
    x = ((x & 0x3333333333333333ull) << 2) | ((x & 0xccccccccccccccccull) >> 2);
    x = ((x & 0x5555555555555555ull) << 1) | ((x & 0xaaaaaaaaaaaaaaaaull) >> 1);
    return x;
}

/* Second Sobol dimension, bit-reversed.  With the polynomial x + 1 (degree 1,
 * m_1 = 1) the direction numbers follow v_k = v_{k-1} ^ (v_{k-1} >> 1),
 * v_0 = 2^31 (Bratley & Fox 1988; Joe & Kuo 2008): the rows of Pascal's
 * triangle mod 2, so output bit j (counted from the top) is the XOR of the
 * index bits k with C(k, j) odd, i.e. (Lucas' theorem) with j a bit-subset of
 * k.  That "superset XOR" transform takes five shift-and-mask steps, one per
 * bit of j, and yields the result bit-reversed (bit j at position j). */
static inline uint32_t sobol_dim1_reversed(uint32_t index)
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
static inline uint32_t laine_karras(uint32_t x, uint32_t seed)
{
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/* Nested uniform Owen scrambling of a value given bit-reversed (Burley 2020,
 * listing 2: reverse, permute, reverse back); the result is in normal order. */
static inline uint32_t owen_scramble_reversed(uint32_t reversed, uint32_t seed)
{
    return reverse_bits(laine_karras(reversed, seed));
}

void il_sampler_start(il_sampler *s, il_sampler_type type, uint64_t seed, uint64_t pixel,
                      uint32_t sample_index)
{
    s->type = type;
    s->seed = seed;
    s->pixel = pixel;
    s->index = sample_index;
    s->index_reversed = reverse_bits(sample_index);
    s->dim = 0;
    s->key = il_hash_combine(il_hash64(seed), pixel);
    /* The PCG stream is only seeded when it is used. */
    if (type == IL_SAMPLER_PCG)
        s->rng = il_pcg32_seed(il_hash_combine(s->key, sample_index), 0x5851f42d4c957f2dull);
    else
        s->rng = (il_pcg32){0u, 0u};
}

/* The scrambling seeds of the pair of dimensions (dim, dim+1): three 32-bit
 * seeds from one 64-bit hash of (pixel key, dimension), the two halves and a
 * third from one more multiplication. */
typedef struct pair_seeds { uint32_t x, y, shuffle; } pair_seeds;

static inline pair_seeds pair_seeds_of(const il_sampler *s, uint32_t dim)
{
    uint64_t key = il_hash64(s->key + 0x9e3779b97f4a7c15ull * (uint64_t)(dim + 1));
    return (pair_seeds){(uint32_t)key, (uint32_t)(key >> 32),
                        (uint32_t)((key * 0xda942042e4dd58b5ull) >> 32)};
}

/* The shuffled sample index of a pair: the index Owen-scrambled with the
 * pair's own seed (Burley section 4).  reverse(index) is computed once per
 * sample in il_sampler_start. */
static inline uint32_t shuffled_index(const il_sampler *s, pair_seeds k)
{
    return owen_scramble_reversed(s->index_reversed, k.shuffle);
}

/* The pair of dimensions (dim, dim+1) of the scrambled, shuffled sequence.
 * Dimension 0 of Sobol is reverse_bits(i), so scrambling it needs no
 * reversal at all. */
static inline il_vec2 sobol_pair(const il_sampler *s, uint32_t dim)
{
    pair_seeds k = pair_seeds_of(s, dim);
    uint32_t i = shuffled_index(s, k);
    /* owen_scramble_reversed for both members, the two bit reversals done
     * together: x in the low half goes to the high half and y vice versa. */
    uint64_t h = (uint64_t)laine_karras(i, k.x) |
                 (uint64_t)laine_karras(sobol_dim1_reversed(i), k.y) << 32;
    uint64_t r = reverse_bits_pair_swapped(h);
    return v2(il_u32_to_float((uint32_t)(r >> 32)), il_u32_to_float((uint32_t)r));
}

/* The first member of the pair alone: the same value as sobol_pair(s, dim).x
 * without the work of the second. */
static inline float sobol_first(const il_sampler *s, uint32_t dim)
{
    pair_seeds k = pair_seeds_of(s, dim);
    return il_u32_to_float(owen_scramble_reversed(shuffled_index(s, k), k.x));
}

il_vec2 il_sampler_2d(il_sampler *s)
{
    uint32_t dim = s->dim;
    s->dim += 2;
    if (s->type == IL_SAMPLER_PCG) {
        float a = il_pcg32_float(&s->rng);
        float b = il_pcg32_float(&s->rng);
        return v2(a, b);
    }
    return sobol_pair(s, dim);
}

void il_sampler_2d_n(il_sampler *s, il_vec2 *out, uint32_t n)
{
    if (s->type == IL_SAMPLER_PCG) {
        for (uint32_t j = 0; j < n; j++)
            out[j] = il_sampler_2d(s);
        return;
    }
    /* Independent pairs: written as one loop so their hash chains overlap. */
    uint32_t dim = s->dim;
    s->dim += 2 * n;
    for (uint32_t j = 0; j < n; j++)
        out[j] = sobol_pair(s, dim + 2 * j);
}

/* One dimension from a fresh pair: Burley's pairs are stratified jointly, so
 * the second member is simply not used (nor computed). */
float il_sampler_1d(il_sampler *s)
{
    uint32_t dim = s->dim;
    s->dim += 2;
    if (s->type == IL_SAMPLER_PCG)
        return il_pcg32_float(&s->rng);
    return sobol_first(s, dim);
}

il_vec2 il_sobol02(uint32_t index)
{
    return v2(il_u32_to_float(reverse_bits(index)),
              il_u32_to_float(reverse_bits(sobol_dim1_reversed(index))));
}
