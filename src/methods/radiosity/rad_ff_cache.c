/* The form-factor row cache: each stored row is one allocation (header,
 * indices and values together), published with an atomic pointer so readers
 * need no lock.  The byte budget is reserved with a compare-and-swap before
 * the copy, so the cap holds under any number of threads. */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/radiosity/rad.h"

/* What malloc adds per block on glibc (a size word, 16-byte granularity). */
#define IL_FF_CACHE_MALLOC_OVERHEAD 16u

struct il_ff_cache {
    uint32_t num_patches;
    size_t cap;
    atomic_size_t bytes;
    _Atomic(il_ff_row *) *rows;
};

il_status il_ff_cache_create(uint32_t num_patches, size_t cap_bytes, il_ff_cache **out,
                             il_error *err)
{
    *out = NULL;
    il_ff_cache *c = il_calloc(1, sizeof *c, err);
    if (!c)
        return IL_ERR_MEMORY;
    c->num_patches = num_patches;
    c->cap = cap_bytes;
    atomic_init(&c->bytes, 0);
    c->rows = il_calloc(num_patches ? num_patches : 1, sizeof *c->rows, err);
    if (!c->rows) {
        free(c);
        return IL_ERR_MEMORY;
    }
    for (uint32_t i = 0; i < num_patches; i++)
        atomic_init(&c->rows[i], NULL);
    *out = c;
    return IL_OK;
}

void il_ff_cache_release(il_ff_cache *cache)
{
    if (!cache)
        return;
    for (uint32_t i = 0; i < cache->num_patches; i++)
        free(atomic_load_explicit(&cache->rows[i], memory_order_relaxed));
    free(cache->rows);
    free(cache);
}

const il_ff_row *il_ff_cache_get(const il_ff_cache *cache, uint32_t i)
{
    if (!cache || i >= cache->num_patches)
        return NULL;
    /* The cast drops const only to satisfy atomic_load's prototype. */
    return atomic_load_explicit((_Atomic(il_ff_row *) *)&cache->rows[i], memory_order_acquire);
}

static size_t row_bytes(uint32_t count)
{
    return sizeof(il_ff_row) + (size_t)count * (sizeof(uint32_t) + sizeof(float)) +
           IL_FF_CACHE_MALLOC_OVERHEAD;
}

bool il_ff_cache_put(il_ff_cache *cache, uint32_t i, const il_ff_row *row)
{
    if (!cache || !row || i >= cache->num_patches)
        return false;
    if (atomic_load_explicit(&cache->rows[i], memory_order_acquire))
        return true; /* already there (another thread computed it too) */
    size_t need = row_bytes(row->count);
    size_t have = atomic_load_explicit(&cache->bytes, memory_order_relaxed);
    do {
        if (need > cache->cap || have > cache->cap - need)
            return false;
    } while (!atomic_compare_exchange_weak_explicit(&cache->bytes, &have, have + need,
                                                    memory_order_relaxed, memory_order_relaxed));
    il_ff_row *copy = malloc(need - IL_FF_CACHE_MALLOC_OVERHEAD);
    if (!copy) {
        atomic_fetch_sub_explicit(&cache->bytes, need, memory_order_relaxed);
        return false;
    }
    /* Values first (4-byte aligned after the 8-byte-aligned header), then indices. */
    copy->count = row->count;
    copy->value = (float *)(copy + 1);
    copy->index = (uint32_t *)(copy->value + row->count);
    if (row->count) {
        memcpy(copy->value, row->value, row->count * sizeof(float));
        memcpy(copy->index, row->index, row->count * sizeof(uint32_t));
    }
    il_ff_row *expected = NULL;
    if (!atomic_compare_exchange_strong_explicit(&cache->rows[i], &expected, copy,
                                                 memory_order_release, memory_order_acquire)) {
        /* Another thread stored row i first: keep that one. */
        free(copy);
        atomic_fetch_sub_explicit(&cache->bytes, need, memory_order_relaxed);
    }
    return true;
}

size_t il_ff_cache_bytes(const il_ff_cache *cache)
{
    return cache ? atomic_load_explicit((atomic_size_t *)&cache->bytes, memory_order_relaxed) : 0;
}
