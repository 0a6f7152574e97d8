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

/* The scalar bit tricks are the GPU kernel's (one source, kernel_sobol.h). */
#include "kernel/kernel_sobol.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define IL_SAMPLER_AVX2 1
#endif

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

/* Nested uniform Owen scrambling of a value given bit-reversed (Burley 2020,
 * listing 2: reverse, permute, reverse back); the result is in normal order. */
static inline uint32_t owen_scramble_reversed(uint32_t reversed, uint32_t seed)
{
    return ilk_reverse_bits(ilk_laine_karras(reversed, seed));
}

void il_sampler_start(il_sampler *s, il_sampler_type type, uint64_t seed, uint64_t pixel,
                      uint32_t sample_index)
{
    s->type = type;
    s->seed = seed;
    s->pixel = pixel;
    s->index = sample_index;
    s->index_reversed = ilk_reverse_bits(sample_index);
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
 * Dimension 0 of Sobol is ilk_reverse_bits(i), so scrambling it needs no
 * reversal at all. */
static inline il_vec2 sobol_pair(const il_sampler *s, uint32_t dim)
{
    pair_seeds k = pair_seeds_of(s, dim);
    uint32_t i = shuffled_index(s, k);
    /* owen_scramble_reversed for both members, the two bit reversals done
     * together: x in the low half goes to the high half and y vice versa. */
    uint64_t h = (uint64_t)ilk_laine_karras(i, k.x) |
                 (uint64_t)ilk_laine_karras(ilk_sobol_dim1_reversed(i), k.y) << 32;
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

/* ---- many samplers at once ----
 *
 * The 32-bit work of sobol_pair (three Laine-Karras hashes, three bit
 * reversals, the dimension-1 transform) done on eight pairs at a time in
 * AVX2 lanes, integer operations with the same results bit for bit; the
 * 64-bit seed hash stays scalar.  The target attribute compiles just these
 * functions for AVX2 (no -march) and il_sampler_2d_gather calls them only
 * when the CPU reports AVX2. */
#ifdef IL_SAMPLER_AVX2
#define IL_AVX2 __attribute__((target("avx2")))

IL_AVX2 static inline __m256i lk8(__m256i x, __m256i seed)
{
    x = _mm256_add_epi32(x, seed);
    x = _mm256_xor_si256(x, _mm256_mullo_epi32(x, _mm256_set1_epi32((int)0x6c50b47cu)));
    x = _mm256_xor_si256(x, _mm256_mullo_epi32(x, _mm256_set1_epi32((int)0xb82f1e52u)));
    x = _mm256_xor_si256(x, _mm256_mullo_epi32(x, _mm256_set1_epi32((int)0xc7afe638u)));
    x = _mm256_xor_si256(x, _mm256_mullo_epi32(x, _mm256_set1_epi32((int)0x8d22f6e6u)));
    return x;
}

/* ilk_reverse_bits on each lane: the bytes swapped by a shuffle, then each
 * byte's bits reversed by two 16-entry table look-ups (one per nibble). */
IL_AVX2 static inline __m256i reverse8(__m256i x)
{
    const __m256i bswap = _mm256_setr_epi8(3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12,
                                           3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12);
    /* rev4[v]: the 4 bits of v reversed; rev4_hi: the same shifted to the top nibble. */
    const __m256i rev4 = _mm256_setr_epi8(0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15,
                                          0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15);
    const __m256i rev4_hi = _mm256_slli_epi16(rev4, 4); /* no carry: entries < 16 */
    const __m256i low = _mm256_set1_epi8(0x0f);
    x = _mm256_shuffle_epi8(x, bswap);
    __m256i lo = _mm256_and_si256(x, low);
    __m256i hi = _mm256_and_si256(_mm256_srli_epi16(x, 4), low);
    return _mm256_or_si256(_mm256_shuffle_epi8(rev4_hi, lo), _mm256_shuffle_epi8(rev4, hi));
}

IL_AVX2 static inline __m256i sobol_dim1_reversed8(__m256i i)
{
    i = _mm256_xor_si256(i, _mm256_and_si256(_mm256_srli_epi32(i, 1), _mm256_set1_epi32(0x55555555)));
    i = _mm256_xor_si256(i, _mm256_and_si256(_mm256_srli_epi32(i, 2), _mm256_set1_epi32(0x33333333)));
    i = _mm256_xor_si256(i, _mm256_and_si256(_mm256_srli_epi32(i, 4), _mm256_set1_epi32(0x0f0f0f0f)));
    i = _mm256_xor_si256(i, _mm256_and_si256(_mm256_srli_epi32(i, 8), _mm256_set1_epi32(0x00ff00ff)));
    i = _mm256_xor_si256(i, _mm256_and_si256(_mm256_srli_epi32(i, 16), _mm256_set1_epi32(0x0000ffff)));
    return i;
}

/* il_u32_to_float on each lane: (x >> 8) is below 2^24, so the signed
 * conversion is exact, and the scaling by 2^-24 too. */
IL_AVX2 static inline __m256 to_float8(__m256i x)
{
    return _mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_srli_epi32(x, 8)), _mm256_set1_ps(0x1p-24f));
}

/* sobol_pair for eight lanes: reversed sample index, pair seeds; out gets
 * x0 y0 x1 y1 ... */
IL_AVX2 static void sobol_pairs8(const uint32_t *index_reversed, const uint32_t *sx,
                                 const uint32_t *sy, const uint32_t *sshuffle, float *out)
{
    __m256i ir = _mm256_loadu_si256((const __m256i *)index_reversed);
    __m256i i = reverse8(lk8(ir, _mm256_loadu_si256((const __m256i *)sshuffle)));
    __m256i hx = lk8(i, _mm256_loadu_si256((const __m256i *)sx));
    __m256i hy = lk8(sobol_dim1_reversed8(i), _mm256_loadu_si256((const __m256i *)sy));
    __m256 fx = to_float8(reverse8(hx)), fy = to_float8(reverse8(hy));
    /* Interleave: unpack works within 128-bit halves, so fix the order of
     * the halves after. */
    __m256 a = _mm256_unpacklo_ps(fx, fy), b = _mm256_unpackhi_ps(fx, fy);
    _mm256_storeu_ps(out, _mm256_permute2f128_ps(a, b, 0x20));
    _mm256_storeu_ps(out + 8, _mm256_permute2f128_ps(a, b, 0x31));
}

/* The Sobol samplers' pairs in groups of eight lanes; PCG ones one by one. */
IL_AVX2 static void gather_avx2(il_sampler *base, const uint32_t *idx, uint32_t n, uint32_t pairs,
                                il_vec2 *out)
{
    uint32_t ir[8], sx[8], sy[8], sh[8];
    il_vec2 *dst[8];
    float res[16];
    uint32_t lanes = 0;
    for (uint32_t k = 0; k < n; k++) {
        il_sampler *s = &base[idx[k]];
        if (s->type == IL_SAMPLER_PCG) {
            il_sampler_2d_n(s, out + (size_t)k * pairs, pairs);
            continue;
        }
        for (uint32_t j = 0; j < pairs; j++) {
            pair_seeds ps = pair_seeds_of(s, s->dim + 2 * j);
            ir[lanes] = s->index_reversed;
            sx[lanes] = ps.x;
            sy[lanes] = ps.y;
            sh[lanes] = ps.shuffle;
            dst[lanes] = out + (size_t)k * pairs + j;
            if (++lanes == 8) {
                sobol_pairs8(ir, sx, sy, sh, res);
                for (uint32_t l = 0; l < 8; l++)
                    *dst[l] = v2(res[2 * l], res[2 * l + 1]);
                lanes = 0;
            }
        }
        s->dim += 2 * pairs;
    }
    if (lanes > 0) {
        /* The last lanes repeat lane 0's numbers, their results unused. */
        for (uint32_t l = lanes; l < 8; l++) {
            ir[l] = ir[0];
            sx[l] = sx[0];
            sy[l] = sy[0];
            sh[l] = sh[0];
        }
        sobol_pairs8(ir, sx, sy, sh, res);
        for (uint32_t l = 0; l < lanes; l++)
            *dst[l] = v2(res[2 * l], res[2 * l + 1]);
    }
}
#endif

void il_sampler_2d_gather(il_sampler *base, const uint32_t *idx, uint32_t n, uint32_t pairs,
                          il_vec2 *out)
{
#ifdef IL_SAMPLER_AVX2
    if (__builtin_cpu_supports("avx2")) {
        gather_avx2(base, idx, n, pairs, out);
        return;
    }
#endif
    for (uint32_t k = 0; k < n; k++)
        il_sampler_2d_n(&base[idx[k]], out + (size_t)k * pairs, pairs);
}

il_vec2 il_sobol02(uint32_t index)
{
    return v2(il_u32_to_float(ilk_reverse_bits(index)),
              il_u32_to_float(ilk_reverse_bits(ilk_sobol_dim1_reversed(index))));
}
