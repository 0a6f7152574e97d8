/* Balanced kd-tree over the photons (Jensen 2001, "Realistic Image Synthesis
 * Using Photon Mapping", 6.3): a left-balanced tree stored as a heap (node i
 * has children 2i+1 and 2i+2), so no child pointers are kept; each node's
 * split axis lives in bits 14-15 of its photon's `normal`.
 *
 * Build: the photons of a subtree are split at the median along the largest
 * extent of their bounding box by selection (O(n) expected), which gives an
 * in-order layout in O(n log n); one permutation pass then moves every
 * photon to its heap slot. */
#include <string.h>

#include "methods/distrib.h"
#include "methods/photon/pm_internal.h"

/* Nodes in the left subtree of a left-balanced tree of n nodes: a complete
 * binary tree whose last level is filled from the left. */
static size_t left_size(size_t n)
{
    if (n <= 1)
        return 0;
    size_t h = 0;                          /* levels below the root */
    while (((size_t)2 << h) <= n)
        h++;
    size_t half_last = (size_t)1 << (h - 1);   /* last-level slots under the left child */
    size_t last = n - (((size_t)1 << h) - 1);  /* nodes on the last level */
    return (half_last - 1) + (last < half_last ? last : half_last);
}

static void swap_ph(il_photon *a, il_photon *b)
{
    il_photon t = *a;
    *a = *b;
    *b = t;
}

/* Rearranges a[0..n-1] so that a[k] holds the value of rank k along axis,
 * smaller-or-equal keys before it and greater-or-equal after (Hoare's
 * FIND with a three-way partition, so runs of equal keys end it at once).
 * The pivot is the median of three; after many unlucky rounds a position
 * from a fixed hash sequence, so no input is quadratic in practice. */
static void select_nth(il_photon *a, size_t n, size_t k, unsigned axis)
{
    size_t lo = 0, hi = n;
    uint64_t h = 0x9E3779B97F4A7C15ull;
    unsigned rounds = 0;
    while (hi - lo > 1) {
        float v;
        if (++rounds < 64) {
            float x = a[lo].p[axis], y = a[lo + (hi - lo) / 2].p[axis], z = a[hi - 1].p[axis];
            v = x < y ? (y < z ? y : (x < z ? z : x)) : (x < z ? x : (y < z ? z : y));
        } else {
            h ^= h >> 31;
            h *= 0xBF58476D1CE4E5B9ull;
            v = a[lo + (size_t)(h % (hi - lo))].p[axis];
        }
        /* [lo,lt) < v, [lt,i) == v, [gt,hi) > v */
        size_t lt = lo, i = lo, gt = hi;
        while (i < gt) {
            float key = a[i].p[axis];
            if (key < v)
                swap_ph(&a[lt++], &a[i++]);
            else if (key > v)
                swap_ph(&a[i], &a[--gt]);
            else
                i++;
        }
        if (k < lt)
            hi = lt;
        else if (k >= gt)
            lo = gt;
        else
            return;
    }
}

#define KD_TASK_MIN 65536

/* One node of the build (n > 1): the median of a[0..n-1] along the largest
 * extent of their box moves to a[left_size(n)], smaller before, larger
 * after, and is tagged with the axis.  Returns left_size(n). */
static size_t split_node(il_photon *a, size_t n)
{
    float lo[3] = {a[0].p[0], a[0].p[1], a[0].p[2]};
    float hi[3] = {lo[0], lo[1], lo[2]};
    for (size_t i = 1; i < n; i++) {
        for (int c = 0; c < 3; c++) {
            float x = a[i].p[c];
            lo[c] = x < lo[c] ? x : lo[c];
            hi[c] = x > hi[c] ? x : hi[c];
        }
    }
    /* Split along the largest extent of the subtree's box (Jensen 6.3.1). */
    unsigned axis = 0;
    float ext = hi[0] - lo[0];
    for (unsigned c = 1; c < 3; c++) {
        if (hi[c] - lo[c] > ext) {
            ext = hi[c] - lo[c];
            axis = c;
        }
    }
    size_t m = left_size(n);
    select_nth(a, n, m, axis);
    il_pm_set_axis(&a[m], axis);
    return m;
}

/* The subtree of a[0..n-1] in in-order layout: its root at left_size(n).
 * Recursion depth is the tree's height (at most 32 for 2^32 photons). */
static void build_inorder(il_photon *a, size_t n)
{
    while (n > 1) {
        size_t m = split_node(a, n);
        size_t nr = n - m - 1;
        if (n >= KD_TASK_MIN) {
            /* Big subtrees: the left half as a task for another thread.
             * Subtrees are disjoint and each is built the same way by any
             * thread, so the tree does not depend on the thread count. */
#pragma omp task default(none) firstprivate(a, m)
            build_inorder(a, m);
            a += m + 1;
            n = nr;
        } else if (m <= nr) {
            /* Recurse into the smaller side, loop on the larger. */
            build_inorder(a, m);
            a += m + 1;
            n = nr;
        } else {
            build_inorder(a + m + 1, nr);
            n = m;
        }
    }
    if (n == 1)
        il_pm_set_axis(&a[0], 0);
}

/* dest[in-order position] = heap index, for the subtree of n nodes rooted at
 * heap index `node` whose photons are at in-order positions lo.. */
static void heap_slots(uint32_t *dest, size_t lo, size_t n, size_t node)
{
    while (n > 0) {
        size_t m = left_size(n);
        dest[lo + m] = (uint32_t)node;
        heap_slots(dest, lo, m, 2 * node + 1);
        lo += m + 1;
        n -= m + 1;
        node = 2 * node + 2;
    }
}

void il_pm_permute(il_photon *photons, uint32_t *dest, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        while (dest[i] != i) {
            uint32_t d = dest[i];
            swap_ph(&photons[i], &photons[d]);
            dest[i] = dest[d];
            dest[d] = d;
        }
    }
}

il_status il_pm_kd_build(il_photon *photons, size_t n, il_error *err)
{
    if (n == 0)
        return IL_OK;
    uint32_t *dest = il_malloc(n * sizeof *dest, err);
    if (!dest)
        return IL_ERR_MEMORY;
#pragma omp parallel if (n >= KD_TASK_MIN)
#pragma omp single
    build_inorder(photons, n);
    heap_slots(dest, 0, n, 0);
    il_pm_permute(photons, dest, n);
    free(dest);
    return IL_OK;
}

/* The top `levels` levels of build_inorder over a[0..n-1] (base: the whole
 * array), the same splits in the same order; the subtrees below them are
 * appended to ranges as (offset, size) pairs, left to right. */
static void build_top(il_photon *base, il_photon *a, size_t n, unsigned levels, size_t *ranges,
                      size_t *count)
{
    if (levels == 0 || n <= 1) {
        ranges[2 * *count] = (size_t)(a - base);
        ranges[2 * *count + 1] = n;
        (*count)++;
        return;
    }
    size_t m = split_node(a, n);
    build_top(base, a, m, levels - 1, ranges, count);
    build_top(base, a + m + 1, n - m - 1, levels - 1, ranges, count);
}

/* The process that builds subtree j of `count`: contiguous runs in order. */
static int subtree_owner(size_t j, size_t count, int size)
{
    return (int)(j * (size_t)size / count);
}

il_status il_pm_kd_build_split(il_photon *photons, size_t n, const il_distrib *d, il_error *err)
{
    /* Small maps: building is cheaper than exchanging (the same choice on
     * every process: n is the same everywhere). */
    if (!il_distrib_on(d) || n < IL_PM_KD_SPLIT_MIN)
        return il_pm_kd_build(photons, n, err);
    /* Twice as many subtrees as processes, so that uneven halves even out
     * a little; the levels above them are split on every process. */
    unsigned levels = 1;
    while (((size_t)1 << levels) < 2 * (size_t)d->size)
        levels++;
    size_t cap = (size_t)1 << levels, count = 0;
    size_t *ranges = il_malloc(2 * cap * sizeof *ranges, err);
    size_t *counts = il_calloc((size_t)d->size, sizeof *counts, err);
    uint32_t *dest = il_malloc(n * sizeof *dest, err);
    if (!ranges || !counts || !dest) {
        free(ranges);
        free(counts);
        free(dest);
        return IL_ERR_MEMORY;
    }
    build_top(photons, photons, n, levels, ranges, &count);
    /* This process's subtrees, each built as build_inorder builds it in a
     * single process; then all of them, in subtree order, to everyone. */
    size_t bytes = 0;
    for (size_t j = 0; j < count; j++)
        if (subtree_owner(j, count, d->size) == d->rank)
            bytes += ranges[2 * j + 1] * sizeof(il_photon);
#pragma omp parallel if (bytes >= KD_TASK_MIN * sizeof(il_photon))
#pragma omp single
    for (size_t j = 0; j < count; j++)
        if (subtree_owner(j, count, d->size) == d->rank) {
            il_photon *a = photons + ranges[2 * j];
            size_t m = ranges[2 * j + 1];
#pragma omp task default(none) firstprivate(a, m)
            build_inorder(a, m);
        }
    unsigned char *send = il_malloc(bytes ? bytes : 1, err);
    il_status st = send ? IL_OK : IL_ERR_MEMORY;
    void *all = NULL;
    if (st == IL_OK) {
        size_t off = 0;
        for (size_t j = 0; j < count; j++)
            if (subtree_owner(j, count, d->size) == d->rank) {
                memcpy(send + off, photons + ranges[2 * j], ranges[2 * j + 1] * sizeof(il_photon));
                off += ranges[2 * j + 1] * sizeof(il_photon);
            }
        st = il_distrib_allgather(d, send, bytes, &all, counts, err);
    }
    /* Every subtree back into its place: rank r's subtrees are the run
     * j with subtree_owner(j) == r, in order, and rank order is j order. */
    size_t off = 0, want = 0;
    for (size_t j = 0; st == IL_OK && j < count; j++)
        want += ranges[2 * j + 1] * sizeof(il_photon);
    size_t got = 0;
    for (int r = 0; st == IL_OK && r < d->size; r++)
        got += counts[r];
    if (st == IL_OK && got != want)
        st = il_fail(err, IL_ERR_RUNTIME, "photon map: the processes sent %zu bytes of subtrees, not %zu",
                     got, want);
    for (size_t j = 0; st == IL_OK && j < count; j++) {
        size_t b = ranges[2 * j + 1] * sizeof(il_photon);
        memcpy(photons + ranges[2 * j], (const unsigned char *)all + off, b);
        off += b;
    }
    free(all);
    free(send);
    free(counts);
    free(ranges);
    if (st == IL_OK) {
        heap_slots(dest, 0, n, 0);
        il_pm_permute(photons, dest, n);
    }
    free(dest);
    return st;
}

/* ----------------------------------------------------------------- queries */

/* Subtrees still to visit: the far child and its split plane's distance. */
typedef struct kd_pending {
    size_t node;
    float d2;
} kd_pending;

/* Nearest-first descent with an explicit stack (Jensen 6.3.2's recursive
 * locate_photons, unrolled).  `visit` sees every photon whose subtree could
 * hold one within *bound; *bound may shrink as it goes.  The plane distance
 * is the very term il_pm_dist2 adds for that axis, so a far subtree is
 * skipped only when none of its photons can pass the d2 <= bound test. */
#define KD_TRAVERSE(photons, n, q, bound, VISIT)                                             \
    do {                                                                                     \
        kd_pending stack_[64];                                                               \
        unsigned sp_ = 0;                                                                    \
        size_t node_ = 0;                                                                    \
        for (;;) {                                                                           \
            while (node_ < (n)) {                                                            \
                const il_photon *ph_ = &(photons)[node_];                                    \
                float d2_ = il_pm_dist2(ph_, (q));                                           \
                if (d2_ <= (bound)) {                                                        \
                    VISIT((uint32_t)node_, d2_);                                             \
                }                                                                            \
                size_t l_ = 2 * node_ + 1;                                                   \
                if (l_ >= (n))                                                               \
                    break;                                                                   \
                unsigned ax_ = il_pm_axis(ph_);                                              \
                float delta_ = (q)[ax_] - ph_->p[ax_];                                       \
                size_t near_ = delta_ < 0.0f ? l_ : l_ + 1;                                  \
                size_t far_ = delta_ < 0.0f ? l_ + 1 : l_;                                   \
                if (far_ < (n))                                                              \
                    stack_[sp_++] = (kd_pending){far_, delta_ * delta_};                     \
                node_ = near_;                                                               \
            }                                                                                \
            node_ = (size_t)-1;                                                              \
            while (sp_ > 0) {                                                                \
                kd_pending it_ = stack_[--sp_];                                              \
                if (it_.d2 <= (bound)) {                                                     \
                    node_ = it_.node;                                                        \
                    break;                                                                   \
                }                                                                            \
            }                                                                                \
            if (node_ == (size_t)-1)                                                         \
                break;                                                                       \
        }                                                                                    \
    } while (0)

uint32_t il_pm_kd_knn(const il_photon *photons, size_t n, il_vec3 p, uint32_t k, float max_d2,
                      il_pm_neighbour *out, float *r2)
{
    il_pm_knn_heap h = {out, k, 0, max_d2};
    if (n > 0 && k > 0) {
        const float q[3] = {p.x, p.y, p.z};
#define KNN_VISIT(i, d2) il_pm_heap_offer(&h, (i), (d2))
        KD_TRAVERSE(photons, n, q, h.bound, KNN_VISIT);
#undef KNN_VISIT
    }
    if (r2)
        *r2 = (k > 0 && h.count == k) ? h.items[0].d2 : max_d2;
    return h.count;
}

bool il_pm_kd_range(const il_photon *photons, size_t n, il_vec3 p, float d2, il_pm_buffer *out)
{
    bool ok = true;
    if (n > 0) {
        const float q[3] = {p.x, p.y, p.z};
/* Out of memory: the traversal runs on, storing nothing more. */
#define RANGE_VISIT(i, dd)                                                                   \
    if (ok && !il_pm_buffer_push(out, (i), (dd)))                                            \
        ok = false;
        KD_TRAVERSE(photons, n, q, d2, RANGE_VISIT);
#undef RANGE_VISIT
    }
    return ok;
}

uint32_t il_pm_kd_nearest_normal(const il_photon *photons, size_t n, il_vec3 p, il_vec3 nrm,
                                 float max_d2)
{
    uint32_t best = UINT32_MAX;
    float bound = max_d2;
    if (n > 0) {
        const float q[3] = {p.x, p.y, p.z};
/* Only points facing the query's way count (the normal test of the
 * estimates); each one found shrinks the search to its distance. */
#define NEAREST_VISIT(i, dd)                                                                 \
    if ((best == UINT32_MAX || (dd) < bound) &&                                              \
        il_pm_normal_agrees(&photons[(i)], nrm)) {                                           \
        best = (i);                                                                          \
        bound = (dd);                                                                        \
    }
        KD_TRAVERSE(photons, n, q, bound, NEAREST_VISIT);
#undef NEAREST_VISIT
    }
    return best;
}
