/* Per-pixel sample streams.  Sobol: Burley 2020, "Practical Hash-based Owen
 * Scrambling" (JCGT 9(4)): Owen-scrambled, shuffled (0,2)-sequence in pairs of
 * dimensions.  PCG: independent uniform numbers.  Both depend only on
 * (seed, pixel, sample index), never on the thread, for determinism. */
#ifndef IL_CORE_SAMPLER_H
#define IL_CORE_SAMPLER_H

#include <stdint.h>
#include "core/rng.h"
#include "core/vec.h"

typedef struct il_sampler {
    il_sampler_type type;
    uint64_t seed;
    uint64_t pixel;
    uint32_t index;       /* sample index within the pixel */
    uint32_t index_reversed; /* reverse_bits(index), for the shuffles */
    uint32_t dim;         /* next dimension */
    il_pcg32 rng;
    uint64_t key;         /* hash(seed, pixel), computed once per sample */
} il_sampler;

void il_sampler_start(il_sampler *s, il_sampler_type type, uint64_t seed, uint64_t pixel,
                      uint32_t sample_index);
float il_sampler_1d(il_sampler *s);
il_vec2 il_sampler_2d(il_sampler *s);
/* n consecutive 2D draws at once: the same numbers as n calls of
 * il_sampler_2d, computed together. */
void il_sampler_2d_n(il_sampler *s, il_vec2 *out, uint32_t n);

/* The next `pairs` 2D draws of each of the samplers base[idx[0..n-1]]: the
 * numbers il_sampler_2d_n(&base[idx[k]], out + k * pairs, pairs) gives,
 * into out[k * pairs + j], computed for many samplers at once (eight lanes
 * of AVX2 where the CPU has it).  Every sampler advances past them. */
void il_sampler_2d_gather(il_sampler *base, const uint32_t *idx, uint32_t n, uint32_t pairs,
                          il_vec2 *out);

/* Point `index` of the plain, unscrambled (0,2)-sequence (Sobol dimensions 0
 * and 1), for tests of its stratification. */
il_vec2 il_sobol02(uint32_t index);

#endif
