/* A block of form-factor rows split across processes (il_distrib, illum.h;
 * docs/distributed.md).  Row k of the block belongs to process k mod N:
 * each process computes the rows it owns that its cache lacks, all
 * processes exchange them in one allgather, and every process keeps every
 * row (and offers it to its cache), so all processes run the same solve on
 * the same rows.  A row depends only on (seed, patch) (il_ff_compute_row),
 * so it is the same bits whoever computes it, and the solution is the
 * single-process one bit for bit.  A row a process still lacks afterwards
 * (its owner found it in its own cache and sent nothing) is computed where
 * it is missing: caches may differ (rows that did not fit under the cap),
 * the rows never do.
 *
 * The wire format per row: uint32 slot k, uint32 count, count uint32
 * indices, count floats. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/distrib.h"
#include "methods/radiosity/rad_solve.h"

/* Computes the rows of the slots in need[0..n) in parallel into their
 * copy slots (and the cache).  Returns false without memory. */
static bool compute_rows(il_rad_rows *rows, const il_ff *ff, il_ff_cache *cache,
                         const uint32_t *patch_of, const uint32_t *need, uint32_t n)
{
    int failed = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(rows->threads) reduction(| : failed)
    for (uint32_t j = 0; j < n; j++) {
        uint32_t k = need[j];
        const il_ff_row *row = il_ff_compute_row(ff, rows->work[omp_get_thread_num()], patch_of[k]);
        il_ff_cache_put(cache, patch_of[k], row);
        if (!il_rad_rows_copy(rows, k, row)) {
            failed |= 1;
            rows->row[k] = NULL;
            continue;
        }
        rows->row[k] = &rows->copy[k];
    }
    return !failed;
}

/* Reads the rows other processes sent into the slots still empty. */
static il_status take_rows(il_rad_rows *rows, il_ff_cache *cache, const uint32_t *patch_of,
                           uint32_t count, const unsigned char *p, size_t bytes, il_error *err)
{
    size_t off = 0;
    while (off < bytes) {
        uint32_t head[2];
        if (bytes - off < sizeof head)
            return il_fail(err, IL_ERR_RUNTIME, "radiosity: a malformed form-factor row arrived");
        memcpy(head, p + off, sizeof head);
        off += sizeof head;
        uint32_t k = head[0], n = head[1];
        if (k >= count || (bytes - off) / 8u < n)
            return il_fail(err, IL_ERR_RUNTIME, "radiosity: a malformed form-factor row arrived");
        if (!rows->row[k]) {
            /* Through a slot of its own, so the data is aligned. */
            il_ff_row *dst = &rows->copy[k];
            if (n > rows->copy_cap[k]) {
                uint32_t *idx = realloc(dst->index, (size_t)n * sizeof *idx);
                if (idx)
                    dst->index = idx;
                float *val = realloc(dst->value, (size_t)n * sizeof *val);
                if (val)
                    dst->value = val;
                if (!idx || !val)
                    return il_fail(err, IL_ERR_MEMORY,
                                   "radiosity: out of memory for form-factor rows");
                rows->copy_cap[k] = n;
            }
            if (n) { /* an empty row may have no arrays */
                memcpy(dst->index, p + off, (size_t)n * sizeof *dst->index);
                memcpy(dst->value, p + off + (size_t)n * 4u, (size_t)n * sizeof *dst->value);
            }
            dst->count = n;
            rows->row[k] = dst;
            il_ff_cache_put(cache, patch_of[k], dst);
        }
        off += (size_t)n * 8u;
    }
    return IL_OK;
}

il_status il_rad_rows_fetch_split(il_rad_rows *rows, const il_ff *ff, il_ff_cache *cache,
                                  const uint32_t *patches, uint32_t first, uint32_t count,
                                  il_radiosity_stats *stats, il_error *err)
{
    const il_distrib *d = rows->distrib;
    double t0 = omp_get_wtime();
    uint32_t *patch_of = il_malloc((size_t)(count ? count : 1) * sizeof *patch_of, err);
    uint32_t *need = il_malloc((size_t)(count ? count : 1) * sizeof *need, err);
    size_t *counts = il_calloc((size_t)d->size, sizeof *counts, err);
    unsigned char *send = NULL;
    void *all = NULL;
    il_status st = patch_of && need && counts ? IL_OK : IL_ERR_MEMORY;
    uint64_t computed = 0;
    uint32_t n = 0;
    if (st == IL_OK) {
        for (uint32_t k = 0; k < count; k++) {
            patch_of[k] = patches ? patches[k] : first + k;
            rows->row[k] = il_ff_cache_get(cache, patch_of[k]);
            if (!rows->row[k] && k % (uint32_t)d->size == (uint32_t)d->rank)
                need[n++] = k;
        }
        if (!compute_rows(rows, ff, cache, patch_of, need, n))
            st = il_fail(err, IL_ERR_MEMORY, "radiosity: out of memory for form-factor rows");
        computed += n;
    }
    /* This process's new rows, in slot order. */
    size_t bytes = 0;
    for (uint32_t j = 0; st == IL_OK && j < n; j++)
        bytes += 8u + (size_t)rows->row[need[j]]->count * 8u;
    if (st == IL_OK && !(send = il_malloc(bytes ? bytes : 1, err)))
        st = IL_ERR_MEMORY;
    if (st == IL_OK) {
        size_t off = 0;
        for (uint32_t j = 0; j < n; j++) {
            const il_ff_row *r = rows->row[need[j]];
            uint32_t head[2] = {need[j], r->count};
            memcpy(send + off, head, sizeof head);
            off += sizeof head;
            if (r->count) { /* an empty row may have no arrays */
                memcpy(send + off, r->index, (size_t)r->count * 4u);
                memcpy(send + off + (size_t)r->count * 4u, r->value, (size_t)r->count * 4u);
            }
            off += (size_t)r->count * 8u;
        }
        st = il_distrib_allgather(d, send, bytes, &all, counts, err);
    }
    size_t off = 0;
    for (int r = 0; st == IL_OK && r < d->size; r++) {
        if (r != d->rank)
            st = take_rows(rows, cache, patch_of, count, (const unsigned char *)all + off,
                           counts[r], err);
        off += counts[r];
    }
    /* What is still missing: the owner had it cached. */
    if (st == IL_OK) {
        n = 0;
        for (uint32_t k = 0; k < count; k++)
            if (!rows->row[k])
                need[n++] = k;
        if (!compute_rows(rows, ff, cache, patch_of, need, n))
            st = il_fail(err, IL_ERR_MEMORY, "radiosity: out of memory for form-factor rows");
        computed += n;
    }
    free(all);
    free(send);
    free(counts);
    free(need);
    free(patch_of);
    if (stats) {
        stats->seconds_form_factors += omp_get_wtime() - t0;
        stats->rows_computed += computed;
    }
    return st;
}
