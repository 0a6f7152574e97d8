/* Hierarchical radiosity split across processes (il_distrib, illum.h;
 * docs/distributed.md, "Hierarchical radiosity").
 *
 * The expensive part of an iteration is the refinement's new links: their
 * form factors (5 contour integrals each) and visibility rays.  Which links
 * the refinement makes depends on the visibility of the links it splits,
 * so they are found in sweeps before it runs:
 *   sweep 0: every link in every list, walked root by root, element by
 *            element in pre-order, in list order; a link whose visibility
 *            is unknown is a request, a known one that splits gives its
 *            children's links as requests (elements split on the way: an
 *            element's children are a pure function of it, hr_elem.c);
 *   sweep k: the requests of sweep k - 1, computed (form factor and
 *            visibility, exactly as il_hr_refine_tree would: il_hr_link_fill
 *            and il_hr_link_visibility, random numbers keyed by the ids)
 *            by the process owning them (request j: process j mod N),
 *            then gathered in rank order; each one that splits gives the
 *            next sweep's requests, in request order.
 * Every process walks the same hierarchy in the same order and reads the
 * same gathered results, so every process makes the same requests, the
 * same elements and the same table.  il_hr_refine_tree then runs as
 * before but takes each new link from the table (il_hr_distrib_take): the
 * same bits as computed in place, so the hierarchy, its link lists and the
 * solution are the single-process ones bit for bit.
 *
 * The table is the requests of all sweeps in order; an entry that splits
 * knows where its replacements start (they were requested together, in
 * refine_link's order), so the refinement follows the chain from link to
 * replacements without a search; only existing links are found by address
 * (a small hash of those that are requests or split).  Every entry taken
 * is checked against the link the refinement makes (receiver, source,
 * parent visibility); one that does not match (none is expected) is
 * computed in place: slower, still the same bits.
 *
 * Wire format per request: float ff, err_ff, vis, vis_bound; uint32 rays
 * (20 bytes).  Not split: sweep 0's walk, the elements' exposure probes,
 * the gather and push-pull (every process runs them on the whole
 * hierarchy), the initial links between roots. */
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/rng.h"
#include "methods/distrib.h"
#include "methods/hr/hr.h"

#define WIRE_BYTES 20u

typedef struct request {
    il_hr_elem *r, *src;
    const il_hr_link *link;  /* an existing link whose visibility is unknown; NULL: a new one */
    bool parent_visible;
} request;

typedef struct entry {
    const il_hr_elem *r, *src;
    float ff, err_ff, vis, vis_bound;
    uint32_t rays;
    uint32_t first_child;       /* the entry of its first replacement; IL_HR_NO_ENTRY: not split */
    bool parent_visible;
} entry;

/* An existing link that the refinement will need: a request of sweep 0
 * (visibility unknown) or one that splits. */
typedef struct old_link {
    const il_hr_link *link;     /* NULL: empty slot */
    const il_hr_elem *r;
    uint32_t entry;             /* its own entry, or IL_HR_NO_ENTRY */
    uint32_t first_child;       /* when entry is none: its first replacement's entry */
} old_link;

struct il_hr_link_table {
    entry *entry;
    size_t count, entry_cap;
    old_link *old;
    size_t old_count, old_cap; /* old_cap a power of two, at least twice old_count */
};

static size_t old_slot(const struct il_hr_link_table *t, const il_hr_link *l)
{
    size_t i = (size_t)il_hash64((uint64_t)(uintptr_t)l) & (t->old_cap - 1);
    while (t->old[i].link && t->old[i].link != l)
        i = (i + 1) & (t->old_cap - 1);
    return i;
}

static const old_link *old_find(const struct il_hr_link_table *t, const il_hr_link *l,
                                const il_hr_elem *r)
{
    if (!t->old_cap)
        return NULL;
    const old_link *o = &t->old[old_slot(t, l)];
    return o->link && o->r == r ? o : NULL;
}

static bool old_put(struct il_hr_link_table *t, const il_hr_link *l, const il_hr_elem *r,
                    uint32_t own, uint32_t first_child)
{
    if (2 * (t->old_count + 1) > t->old_cap) {
        size_t cap = t->old_cap ? 2 * t->old_cap : 1024;
        old_link *n = calloc(cap, sizeof *n), *o = t->old;
        if (!n)
            return false;
        size_t ocap = t->old_cap;
        t->old = n;
        t->old_cap = cap;
        for (size_t i = 0; i < ocap; i++)
            if (o[i].link)
                t->old[old_slot(t, o[i].link)] = o[i];
        free(o);
    }
    old_link *o = &t->old[old_slot(t, l)];
    if (!o->link)
        t->old_count++;
    *o = (old_link){l, r, own, first_child};
    return true;
}

/* Room for `more` entries. */
static bool entries_reserve(struct il_hr_link_table *t, size_t more)
{
    size_t need = t->count + more;
    if (need >= IL_HR_NO_ENTRY)
        return false;
    if (need <= t->entry_cap)
        return true;
    size_t cap = t->entry_cap ? t->entry_cap : 4096;
    while (cap < need)
        cap *= 2;
    entry *e = realloc(t->entry, cap * sizeof *e);
    if (!e)
        return false;
    t->entry = e;
    t->entry_cap = cap;
    return true;
}

static void fill_from(const entry *e, il_hr_pool *pool, il_hr_elem *src, il_hr_link *l)
{
    l->src = src;
    l->ff = e->ff;
    l->err_ff = e->err_ff;
    l->vis = e->vis;
    l->vis_bound = e->vis_bound;
    l->next = NULL;
    pool->vis_rays += e->rays;
}

bool il_hr_distrib_take(const il_hr_solver *s, il_hr_pool *pool, uint32_t at, const il_hr_elem *r,
                        il_hr_elem *src, bool parent_visible, il_hr_link *l)
{
    const struct il_hr_link_table *t = s->table;
    if (!t || at >= t->count)
        return false;
    const entry *e = &t->entry[at];
    if (e->r != r || e->src != src || e->parent_visible != parent_visible)
        return false;
    fill_from(e, pool, src, l);
    return true;
}

bool il_hr_distrib_take_old(const il_hr_solver *s, il_hr_pool *pool, const il_hr_elem *r,
                            il_hr_link *l, bool parent_visible, uint32_t *at)
{
    const old_link *o = s->table ? old_find(s->table, l, r) : NULL;
    if (!o || o->entry == IL_HR_NO_ENTRY ||
        !il_hr_distrib_take(s, pool, o->entry, r, l->src, parent_visible, l))
        return false;
    *at = o->entry;
    return true;
}

uint32_t il_hr_distrib_first_child(const il_hr_solver *s, const il_hr_elem *r,
                                   const il_hr_link *l, uint32_t at)
{
    const struct il_hr_link_table *t = s->table;
    if (!t)
        return IL_HR_NO_ENTRY;
    if (at < t->count)
        return t->entry[at].first_child;
    const old_link *o = old_find(t, l, r);
    if (!o)
        return IL_HR_NO_ENTRY;
    return o->entry != IL_HR_NO_ENTRY ? t->entry[o->entry].first_child : o->first_child;
}

void il_hr_distrib_table_free(il_hr_solver *s)
{
    if (s->table) {
        free(s->table->entry);
        free(s->table->old);
    }
    free(s->table);
    s->table = NULL;
}

/* One sweep's requests; base: the table entry of the first. */
typedef struct request_list {
    request *item;
    size_t count, cap, base;
} request_list;

static bool push(request_list *q, il_hr_elem *r, il_hr_elem *src, const il_hr_link *link, bool pv)
{
    if (q->count == q->cap) {
        size_t cap = q->cap ? 2 * q->cap : 1024;
        request *n = realloc(q->item, cap * sizeof *n);
        if (!n)
            return false;
        q->item = n;
        q->cap = cap;
    }
    q->item[q->count++] = (request){r, src, link, pv};
    return true;
}

/* What il_hr_refine_tree does with link l (receiver r) once its visibility
 * is known: when it splits, the links it is replaced by go to q (in
 * refine_link's order) and *first is the entry of the first of them,
 * else IL_HR_NO_ENTRY.  False when out of memory. */
static bool expand(const il_hr_solver *s, il_hr_elem *r, const il_hr_link *l, request_list *q,
                   uint32_t *first)
{
    *first = IL_HR_NO_ENTRY;
    if (!il_hr_splits(s, r, l, l->vis_bound))
        return true;
    il_hr_elem *src = l->src;
    bool split_receiver = r->area >= src->area;
    il_hr_elem *kids = il_hr_children(s, split_receiver ? r : src, &s->pools[0]);
    if (!kids || q->base + q->count >= IL_HR_NO_ENTRY)
        return false;
    *first = (uint32_t)(q->base + q->count);
    bool visible = l->vis >= 1.0f;
    for (uint32_t k = 0; k < 4; k++) {
        il_hr_elem *rr = split_receiver ? &kids[k] : r, *ss = split_receiver ? src : &kids[k];
        if (il_hr_facing(s, rr, ss) && !push(q, rr, ss, NULL, visible))
            return false;
    }
    return true;
}

/* Sweep 0 over e's subtree: the existing links. */
static bool walk(const il_hr_solver *s, il_hr_elem *e, request_list *q)
{
    struct il_hr_link_table *t = s->table;
    for (const il_hr_link *l = e->links; l; l = l->next) {
        if (l->vis < 0.0f) {
            if (q->base + q->count >= IL_HR_NO_ENTRY ||
                !old_put(t, l, e, (uint32_t)(q->base + q->count), IL_HR_NO_ENTRY) ||
                !push(q, e, l->src, l, false))
                return false;
            continue;
        }
        uint32_t first;
        if (!expand(s, e, l, q, &first) ||
            (first != IL_HR_NO_ENTRY && !old_put(t, l, e, IL_HR_NO_ENTRY, first)))
            return false;
    }
    il_hr_elem *kids = il_hr_children_get(e);
    for (uint32_t k = 0; kids && k < 4; k++)
        if (!walk(s, &kids[k], q))
            return false;
    return true;
}

/* How many of n requests are rank r's of size: j = r, r + size, ... */
static size_t share(size_t n, size_t r, size_t size) { return n > r ? (n - r + size - 1) / size : 0; }

/* A request's link, as il_hr_refine_tree would compute it, into 20 bytes. */
static void compute(const il_hr_solver *s, const request *rq, unsigned char *out)
{
    il_hr_link l;
    if (rq->link)
        l = *rq->link;
    else
        il_hr_link_fill(s, rq->r, rq->src, &l);
    il_hr_pool counter;
    il_hr_pool_init(&counter);
    if (l.vis < 0.0f)
        il_hr_link_visibility(s, &counter, rq->r, &l, rq->parent_visible,
                              il_hr_splits(s, rq->r, &l, 1.0f));
    float f[4] = {l.ff, l.err_ff, l.vis, l.vis_bound};
    uint32_t rays = (uint32_t)counter.vis_rays;
    memcpy(out, f, sizeof f);
    memcpy(out + sizeof f, &rays, sizeof rays);
}

il_status il_hr_distrib_plan(il_hr_solver *s, il_error *err)
{
    const il_distrib *d = s->set.distrib;
    /* Kept from the last refinement (no allocation), emptied. */
    if (!s->table && !(s->table = il_calloc(1, sizeof *s->table, err)))
        return IL_ERR_MEMORY;
    struct il_hr_link_table *t = s->table;
    t->count = 0;
    t->old_count = 0;
    if (t->old_cap)
        memset(t->old, 0, t->old_cap * sizeof *t->old);
    request_list cur = {0}, next = {0};
    il_status st = IL_OK;
    for (uint32_t i = 0; i < s->num_roots && st == IL_OK; i++)
        if (!walk(s, &s->roots[i], &cur))
            st = il_fail(err, IL_ERR_MEMORY, "hr: out of memory while planning the refinement");
    size_t *counts = il_calloc((size_t)d->size, sizeof *counts, err);
    size_t *offset = il_calloc((size_t)d->size, sizeof *offset, err);
    if (!counts || !offset)
        st = IL_ERR_MEMORY;
    /* Every process runs the same number of sweeps: the request lists are
     * the same everywhere, so all stop at the same empty one. */
    while (st == IL_OK && cur.count > 0) {
        /* Request j is rank j mod N's: neighbouring requests (the
         * replacements of one link, the links of one element) cost alike,
         * so every rank gets a like mix; contiguous ranges left one rank
         * with the costlier half of a sweep. */
        size_t n = (size_t)d->size, me = (size_t)d->rank;
        size_t mine = share(cur.count, me, n);
        unsigned char *send = il_malloc(mine ? mine * WIRE_BYTES : 1, err);
        void *all = NULL;
        if (!send) {
            st = IL_ERR_MEMORY;
            break;
        }
#pragma omp parallel for schedule(dynamic, 16) num_threads(s->set.threads)
        for (size_t j = 0; j < mine; j++)
            compute(s, &cur.item[me + j * n], send + j * WIRE_BYTES);
        st = il_distrib_allgather(d, send, mine * WIRE_BYTES, &all, counts, err);
        free(send);
        /* Where each rank's part starts in what arrived. */
        for (size_t r = 0, at = 0; st == IL_OK && r < n; r++) {
            if (counts[r] != share(cur.count, r, n) * WIRE_BYTES)
                st = il_fail(err, IL_ERR_RUNTIME, "hr: process %zu sent %zu bytes of links, not %zu",
                             r, counts[r], share(cur.count, r, n) * WIRE_BYTES);
            offset[r] = at;
            at += counts[r];
        }
        if (st == IL_OK && !entries_reserve(t, cur.count))
            st = il_fail(err, IL_ERR_MEMORY, "hr: out of memory for the distributed links");
        next.count = 0;
        next.base = cur.base + cur.count;
        for (size_t j = 0; st == IL_OK && j < cur.count; j++) {
            const request *rq = &cur.item[j];
            const unsigned char *p =
                (const unsigned char *)all + offset[j % n] + (j / n) * WIRE_BYTES;
            float f[4];
            uint32_t rays;
            memcpy(f, p, sizeof f);
            memcpy(&rays, p + sizeof f, sizeof rays);
            il_hr_link l = {.src = rq->src, .ff = f[0], .err_ff = f[1], .vis = f[2],
                            .vis_bound = f[3]};
            uint32_t first;
            if (!expand(s, rq->r, &l, &next, &first))
                st = il_fail(err, IL_ERR_MEMORY, "hr: out of memory while planning the refinement");
            t->entry[t->count++] = (entry){rq->r, rq->src, f[0], f[1], f[2], f[3], rays, first,
                                           rq->parent_visible};
        }
        free(all);
        request_list tmp = cur;
        cur = next;
        next = tmp;
    }
    free(counts);
    free(offset);
    free(cur.item);
    free(next.item);
    if (st != IL_OK)
        il_hr_distrib_table_free(s);
    return st;
}
