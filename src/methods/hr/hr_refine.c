/* BF refinement, gather and push-pull over one root's quadtree (hr.h).
 *
 * Refinement (Hanrahan, Salzman & Aupperle 1991, section 4; SPLASH-2's
 * "BF refinement"): a link r <- s is split while
 *     err_ff * lum(B_s / exposure_s) * V / B_ref > bf_eps
 * (B_ref: the scene's mean emitted radiance, sum A lum(Le) / sum A, the
 * brightness the surfaces would have if the emitted power were spread over
 * all of them; V: the link's upper bound of visibility, hr_link.c) and the
 * larger element's area exceeds area_eps * diag^2.  The larger of the two
 * is split: a receiver-side split replaces the link by links from each
 * child of r (that faces s) to s, a source-side split by links from r to
 * each child of s (that faces r); the new links are refined in turn.  A
 * link no ray of which could pass (V bound 0) is never split.
 *
 * Visibility rays are cast when a link first comes here (hr_link.c).
 *
 * r's link list is touched by the task refining r's parent (which hands
 * links down to r) and then by r's own task, started after it: the order of
 * every list is fixed; children are shared through il_hr_children
 * (race-free). */
#include <omp.h>

#include "methods/hr/hr.h"

/* Quadtree levels whose children are refined in tasks of their own. */
#define TASK_LEVELS 3

/* Whether the link is split when its visibility bound is vis_bound (the
 * test above, il_hr_splits in hr.h: hr_distrib.c makes the same call). */
static bool splits(const il_hr_solver *s, const il_hr_elem *r, const il_hr_link *l, float vis_bound)
{
    return il_hr_splits(s, r, l, vis_bound);
}

/* parent_visible: the link l replaced had every visibility ray pass;
 * at: split across processes, the table entry l was taken from
 * (IL_HR_NO_ENTRY: an existing link, or one computed here). */
static void refine_link(const il_hr_solver *s, il_hr_pool *pool, il_hr_elem *r, il_hr_link *l,
                        bool parent_visible, uint32_t at)
{
    /* After a stop (il_hr_step_fn) no link is split; each still needs its
     * visibility to be gathered, except in the first refinement, after
     * which nothing is gathered. */
    bool stopping = il_hr_stopping(s);
    /* Split across processes, the table has it (the same bits). */
    if (l->vis < 0.0f && !(stopping && s->stats.iterations == 0) &&
        !(s->table && il_hr_distrib_take_old(s, pool, r, l, parent_visible, &at))) {
        il_hr_link_visibility(s, pool, r, l, parent_visible, splits(s, r, l, 1.0f));
        il_hr_watch_poll(s); /* here, after the rays: a link kept as it was costs next to nothing */
    }
    if (stopping || !splits(s, r, l, l->vis_bound) || pool->failed) {
        il_hr_link_append(r, l);
        return;
    }
    il_hr_elem *src = l->src;
    bool split_receiver = r->area >= src->area;
    il_hr_elem *kids = il_hr_children(s, split_receiver ? r : src, pool);
    if (!kids) {
        il_hr_link_append(r, l);
        return;
    }
    bool visible = l->vis >= 1.0f;
    /* The table's replacements of l follow one another in this order. */
    uint32_t next_at = s->table ? il_hr_distrib_first_child(s, r, l, at) : IL_HR_NO_ENTRY;
    il_hr_pool_put_link(pool, l);
    for (uint32_t k = 0; k < 4; k++) {
        il_hr_elem *rr = split_receiver ? &kids[k] : r, *ss = split_receiver ? src : &kids[k];
        if (!il_hr_facing(s, rr, ss))
            continue;
        il_hr_link *nl = NULL;
        uint32_t nl_at = IL_HR_NO_ENTRY;
        if (s->table) {
            if (!(nl = il_hr_pool_link(pool)))
                return;
            if (next_at != IL_HR_NO_ENTRY &&
                il_hr_distrib_take(s, pool, next_at, rr, ss, visible, nl)) {
                nl_at = next_at++;
            } else {
                next_at = IL_HR_NO_ENTRY;
                il_hr_link_fill(s, rr, ss, nl);
            }
            pool->links_made++;
        } else if (!(nl = il_hr_link_make(s, pool, rr, ss))) {
            return;
        }
        refine_link(s, pool, rr, nl, visible, nl_at);
    }
}

void il_hr_refine_tree(const il_hr_solver *s, il_hr_elem *e)
{
    /* The pool of the thread running this task (tasks are tied: the
     * thread does not change while one runs). */
    il_hr_pool *pool = &s->pools[omp_get_thread_num()];
    il_hr_watch_poll(s);
    if (il_hr_stopping(s)) /* e's links stay as they are (refine_link) */
        return;
    il_hr_link *l = e->links;
    e->links = e->links_tail = NULL;
    e->num_links = 0;
    while (l) {
        il_hr_link *next = l->next;
        refine_link(s, pool, e, l, false, IL_HR_NO_ENTRY);
        l = next;
    }
    /* e's links are final now, and so are the lists it handed down to its
     * children: each child's subtree can go on in a task of its own (only
     * near the root, where subtrees are big enough to pay for a task).
     * Children another task made meanwhile (source-side) have no links:
     * visiting them or not changes nothing. */
    il_hr_elem *kids = il_hr_children_get(e);
    if (!kids)
        return;
    for (uint32_t k = 0; k < 4; k++) {
        il_hr_elem *c = &kids[k];
        if (e->level < TASK_LEVELS && s->set.threads > 1) {
#pragma omp task firstprivate(c)
            il_hr_refine_tree(s, c);
        } else {
            il_hr_refine_tree(s, c);
        }
    }
}

void il_hr_gather_root(il_hr_elem *e)
{
    float h[3] = {0.0f, 0.0f, 0.0f};
    for (const il_hr_link *l = e->links; l; l = l->next) {
        float w = l->ff * l->vis;
        il_vec3 b = il_hr_exposed_radiance(l->src);
        h[0] += w * b.x;
        h[1] += w * b.y;
        h[2] += w * b.z;
    }
    e->gathered = v3(h[0], h[1], h[2]);
    il_hr_elem *kids = il_hr_children_get(e);
    if (kids)
        for (uint32_t k = 0; k < 4; k++)
            il_hr_gather_root(&kids[k]);
}

/* Push (Hanrahan et al. 1991, section 4.3): what an element gathered
 * reaches all its descendants; pull: an inner element's radiance (and
 * exposure) is the area-weighted mean of its children's. */
static void push_pull(il_hr_elem *e, il_vec3 down)
{
    il_vec3 in = v3_add(down, e->gathered);
    il_hr_elem *kids = il_hr_children_get(e);
    if (!kids) {
        e->incoming = in;
        e->radiance = v3_add(e->emit, v3_mul(e->rho, in));
        return;
    }
    il_vec3 b = v3s(0.0f), h = v3s(0.0f);
    float area = 0.0f, exposed = 0.0f;
    for (uint32_t k = 0; k < 4; k++) {
        push_pull(&kids[k], in);
        b = v3_fma(b, kids[k].radiance, kids[k].area);
        h = v3_fma(h, kids[k].incoming, kids[k].area);
        exposed += kids[k].exposure * kids[k].area;
        area += kids[k].area;
    }
    float inv = area > 0.0f ? 1.0f / area : 0.0f;
    e->radiance = v3_scale(b, inv);
    e->incoming = v3_scale(h, inv);
    /* The children's estimates are finer than the element's own. */
    e->exposure = exposed * inv;
}

void il_hr_push_pull_root(il_hr_elem *root) { push_pull(root, v3s(0.0f)); }
