/* The sampling pass (Nilles 2017, sec. 3.3) and the method's entry point.
 *
 * A backward path tracer: mirrors and glass are followed; at a non-delta
 * hit x direct light is taken by a light sample and a shadow ray
 * (scene/direct.h, as the photon mapper does), then one direction wi is
 * drawn from the BSDF and, instead of tracing on, the Linespace is read:
 *
 *   L(x -> wo) = Le + L_direct + f(wo, wi) |cos| / pdf(wi) * L_ls(x, wi)
 *
 * where L_ls is the radiance (W m^-2 sr^-1) stored for the shaft and
 * direction of the line through x along -wi (ls_inject.c).  It holds the
 * light that scattered at least once, so nothing is counted twice: emitters
 * reached by the drawn direction are never added after a non-delta bounce.
 *
 * Variants: the lookup point jittered on a disk of radius `blur` about x in
 * the tangent plane (the thesis's blur); the in-shaft occlusion test (the
 * shaft's candidate triangles between x and the voxel's face: then x does
 * not see what the shaft holds); the fallback (an occluded shaft traces
 * on, as the path tracer, instead of giving nothing; with fallback_empty
 * an empty entry does too, else it reads as no light, the estimator's own
 * value).  Phong lobes sharper than n2 always trace on, below n1 read the
 * Linespace; between, the Linespace is read with probability
 * (n2 - e) / (n2 - n1), which blends the two estimates linearly.  The
 * final gather (Jensen 2001, 9.3.2,
 * as the photon mapper's) traces the first non-delta bounce on and reads
 * at the next non-delta hit, where the field's per-voxel error is averaged
 * over the first hit's hemisphere. */
#include <math.h>
#include <stdatomic.h>
#include <string.h>

#include <omp.h>

#include "core/error.h"
#include "core/sampling.h"
#include "methods/camera_pass.h"
#include "methods/camera_wave.h"
#include "methods/diffuse_wave.h"
#include "methods/distrib.h"
#include "methods/linespace/ls.h"
#include "methods/portal_light.h"
#include "scene/bsdf.h"
#include "scene/direct.h"
#include "scene/lights.h"
#include "trace/trace.h"

typedef struct ls_counts {
    uint64_t lookups, hits, empty, occluded, coarse, outside;
} ls_counts;

typedef struct ls_method {
    const il_scene *scene;
    const il_linespace *ls;
    il_ls_settings set;
    il_ls_test test;               /* which entries the occlusion test runs on */
    float blur_radius;             /* world units */
    bool prefetch;                 /* il_wave_wants_prefetch */
    _Atomic uint64_t lookups, hits, empty, occluded, coarse, outside;
} ls_method;

/* How likely a hit on material `mat` reads the Linespace rather than
 * tracing on. */
static float lookup_probability(const ls_method *m, const il_material *mat)
{
    if (mat->type == IL_MATERIAL_DIFFUSE)
        return 1.0f;
    if (mat->type != IL_MATERIAL_PHONG)
        return 0.0f;
    float e = il_phong_exponent(mat);
    if (e <= m->set.n1)
        return 1.0f;
    if (e >= m->set.n2)
        return 0.0f;
    return (m->set.n2 - e) / (m->set.n2 - m->set.n1);
}

/* One camera path: what il_pt_state is to the path tracer.  A vertex's
 * direct light waits for its shadow ray (traced by the caller, with the
 * wave's others) and what the Linespace gave is added after it. */
typedef struct ls_path {
    il_vec3 L, beta;
    il_ray ray;                    /* the next ray to trace */
    bool specular;                 /* the ray left the camera or a delta lobe */
    bool camera_chain;             /* ... and so did every ray before it */
    bool traced;                   /* a non-delta bounce was traced on, not read */
    bool exterior;                 /* outside: it left by a portal (track_side) */
    uint32_t depth;                /* scattering events before `ray` */
    bool shadow, read;             /* pending: shadow_ray's light, read_L */
    il_ray shadow_ray;
    il_vec3 shadow_L, read_L;
    uint64_t rays;
    /* A lookup waiting for the wave's (path_step returned LS_LOOKUP): at x
     * (geometric normal ng, triangle self) along wi, with the throughput
     * after the bounce and the Russian-roulette number. */
    il_vec3 x, ng, wi, next;
    uint32_t self_mesh, self_prim;
    float rr_u;
} ls_path;

/* What path_step leaves a path to: stop, trace on along p->ray, or the
 * Linespace lookup pending in it (path_after_lookup). */
typedef enum ls_step { LS_STOP, LS_GO, LS_LOOKUP } ls_step;

static void path_begin(ls_path *p, il_vec3 org, il_vec3 dir)
{
    p->L = v3s(0.0f);
    p->beta = v3s(1.0f);
    p->ray = (il_ray){.org = org, .tmin = 0.0f, .dir = dir, .tmax = INFINITY};
    p->specular = p->camera_chain = true;
    p->traced = p->exterior = false;
    p->depth = 0;
    p->shadow = p->read = false;
    p->rays = 1;                   /* the camera ray */
}

/* The path goes on from x along wi (the bounce's throughput already in
 * p->beta), with Russian roulette after the third vertex (pbrt-v4
 * 13.4.4) on rr_u. */
static ls_step path_advance(const il_scene *s, ls_path *p, il_vec3 x, il_vec3 ng, il_vec3 wi, float rr_u)
{
    if (v3_is_zero(p->beta) || !v3_is_finite(p->beta))
        return LS_STOP;
    p->ray = (il_ray){.org = il_offset_origin(s->tracer, x, ng, wi), .tmin = 0.0f, .dir = wi,
                      .tmax = INFINITY};
    if (p->depth >= 3) {
        float q = il_minf(v3_max_comp(p->beta), 0.95f);
        if (!(rr_u < q))
            return LS_STOP;
        p->beta = v3_scale(p->beta, 1.0f / q);
    }
    p->depth++;
    p->rays++;                     /* the next ray */
    return LS_GO;
}

/* A pending lookup's answer r (Li when found, from the coarse level when
 * `coarse`): the path ends with what it read, or (fallback) traces on as
 * the path tracer would. */
static ls_step path_after_lookup(const ls_method *m, ls_path *p, il_ls_lookup_status r, il_vec3 Li,
                                 bool coarse, ls_counts *cnt)
{
    if (r == IL_LS_FOUND) {
        cnt->hits++;
        cnt->coarse += coarse;
        p->read = true;
        p->read_L = v3_mul(p->next, Li);
        return LS_STOP;
    }
    if (r == IL_LS_OCCLUDED)
        cnt->occluded++;
    else
        cnt->empty++;
    if (!m->set.fallback || (r == IL_LS_EMPTY && !m->set.fallback_empty))
        return LS_STOP;
    p->beta = p->next;
    p->specular = p->camera_chain = false;
    p->traced = true;
    return path_advance(m->scene, p, p->x, p->ng, p->wi, p->rr_u);
}

/* With the portals' light the Linespace holds the light inside alone
 * (ls_inject.c), the camera being inside: a path that leaves by a portal
 * is outside, where it traces on as the path tracer, until it enters by
 * one again.  p->ray ended at t_hit. */
static void track_side(const ls_method *m, ls_path *p, float t_hit)
{
    if (!m->ls->portal_light)
        return;
    if (p->exterior ? il_portal_light_enters(m->scene, &p->ray, t_hit)
                    : il_portal_light_leaves(m->scene, &p->ray, t_hit, NULL))
        p->exterior = !p->exterior;
}

/* The vertex where p->ray ended (hit NULL: it left the scene).  u: its four
 * pairs, always drawn in this order (a fifth for the blur is drawn here
 * when a lookup is made), and cos_dir the cosine warp of u[2]; dw, when
 * not NULL, what il_diffuse_wave made of a Lambertian or Phong vertex with them
 * (its light sample, as il_direct_light_sample takes it, and its BSDF
 * sample, bit for bit), so that only the rest is done here.  Returns
 * true when the path goes on along p->ray; either way the caller then
 * resolves the vertex with path_finish_vertex. */
static ls_step path_step(const ls_method *m, ls_path *p, const il_hit *hit, const il_surface *surf,
                         const il_vec2 *u, const il_vec3 *cos_dir, const il_diffuse_out *dw,
                         il_sampler *smp, ls_counts *cnt)
{
    const il_scene *s = m->scene;
    p->shadow = p->read = false;
    if (!hit) {
        if (p->specular)
            p->L = v3_add(p->L, v3_mul(p->beta, p->camera_chain ? il_background_radiance(s, p->ray.dir)
                                                                : il_environment_radiance(s, p->ray.dir)));
        return LS_STOP;
    }
    track_side(m, p, hit->t);
    il_vec3 wo = v3_neg(p->ray.dir);
    const il_material *mat = surf->material;
    if (p->specular && !v3_is_zero(mat->emission))
        p->L = v3_add(p->L, v3_mul(p->beta, il_emitted_radiance(mat, surf->ng, wo)));
    if (p->depth >= m->set.max_depth)
        return LS_STOP;
    /* A vertex whose light and BSDF samples il_diffuse_wave made needs no
     * BSDF of its own. */
    bool made = dw && dw->next_done, nee_made = dw && dw->nee_done;
    il_bsdf b;
    if (!made || !nee_made)
        il_bsdf_init(&b, s, surf);
    il_bsdf_sample bs;
    if (!made && il_bsdf_is_delta(&b)) {
        if (!il_bsdf_sample_dir_cos(&b, wo, u[0].y, u[2], cos_dir, &bs) ||
            !il_sides_agree(surf, wo, bs.wi))
            return LS_STOP;
        p->beta = v3_mul(p->beta, bs.weight);
        p->specular = true;
    } else {
        il_vec3 unblocked;
        if (nee_made) {
            if (dw->shadow) {
                p->shadow = true;
                p->shadow_ray = dw->shadow_ray;
                p->shadow_L = v3_mul(p->beta, dw->shadow_L);
                p->rays++;
            }
        } else if (il_direct_light_sample(s, surf, &b, wo, u[0].x, u[1], &p->shadow_ray, &unblocked)) {
            p->shadow = true;
            p->shadow_L = v3_mul(p->beta, unblocked);
            p->rays++;
        }
        il_vec3 next;
        if (made) {
            if (!dw->next_ok)
                return LS_STOP;
            bs.wi = dw->next_ray.dir;
            next = dw->next_beta;
        } else {
            if (!il_bsdf_sample_dir_cos(&b, wo, u[0].y, u[2], cos_dir, &bs) ||
                !il_sides_agree(surf, wo, bs.wi))
                return LS_STOP;
            next = v3_mul(p->beta, bs.weight);
        }
        /* Where the grid covers only the interior the camera sees, a
         * point outside it has no Linespace: the path traces on there. */
        bool outside = p->exterior || (m->ls->partial && !il_ls_inside(m->ls, surf->p));
        cnt->outside += outside;
        if ((p->traced || !m->set.trace_first_bounce) && u[3].x < lookup_probability(m, mat) && !outside) {
            cnt->lookups++;
            p->x = surf->p;
            p->ng = surf->ng;
            p->wi = bs.wi;
            p->next = next;
            p->self_mesh = surf->mesh;
            p->self_prim = surf->prim;
            p->rr_u = u[3].y;
            if (m->blur_radius <= 0.0f)
                return LS_LOOKUP; /* read with the wave's others */
            il_frame f = il_frame_from_normal(surf->ns);
            il_vec2 d = il_sample_concentric_disk(il_sampler_2d(smp));
            il_vec3 q = v3_fma(v3_fma(surf->p, f.s, m->blur_radius * d.x), f.t, m->blur_radius * d.y);
            il_vec3 Li = v3s(0.0f);
            bool coarse;
            il_ls_lookup_status r = il_ls_lookup(m->ls, q, bs.wi, &Li, &coarse);
            /* The occlusion test where m->test says (il_ls_read_probe). */
            if (il_ls_tested(m->test, r == IL_LS_FOUND) &&
                il_ls_occluded(m->ls, s, surf->p, bs.wi, surf->mesh, surf->prim, &p->rays))
                r = IL_LS_OCCLUDED;
            return path_after_lookup(m, p, r, Li, coarse, cnt);
        }
        p->beta = next;
        p->specular = p->camera_chain = false;
        p->traced = true;
    }
    return path_advance(s, p, surf->p, surf->ng, bs.wi, u[3].y);
}


/* Adds the vertex's direct light (the part its shadow ray let through),
 * then what it read from the Linespace. */
static void path_finish_vertex(ls_path *p, float visible)
{
    if (p->shadow && visible == 1.0f)
        p->L = v3_add(p->L, p->shadow_L);
    else if (p->shadow && visible > 0.0f)
        p->L = v3_fma(p->L, p->shadow_L, visible);
    if (p->read)
        p->L = v3_add(p->L, p->read_L);
    p->shadow = p->read = false;
}

/* A lookup whose occlusion test il_ls_read_probe left as a ray
 * (IL_LS_TRACE, IL_LS_TRACE_EMPTY), once the ray is traced: occluded when
 * it hit, else what the entry holds. */
static il_ls_lookup_status after_occlusion_ray(il_ls_lookup_status left, bool hit)
{
    if (hit)
        return IL_LS_OCCLUDED;
    return left == IL_LS_TRACE ? IL_LS_FOUND : IL_LS_EMPTY;
}

/* Paths advanced together: one 16x16 tile at one sample per pixel. */
#define LS_WAVE 256u
#define LS_PAIRS 4u

/* One wave of camera paths, advanced a vertex at a time with every
 * vertex's rays traced as one stream (the path tracer's wavefront,
 * methods/pt/pt_wavefront.c): the sampler draws, the surfaces and the
 * cosine warps of all paths are computed together.  Each path is the
 * same estimator as a path taken alone, with the same numbers.  Arrays
 * indexed by path are [j], by position in the active list [a]. */
typedef struct ls_wave {
    ls_path path[LS_WAVE];
    il_sampler smp[LS_WAVE];
    uint32_t px[LS_WAVE], py[LS_WAVE];
    uint32_t active[LS_WAVE], stepped[LS_WAVE], drawing[LS_WAVE], shadowed[LS_WAVE];
    float visible[LS_WAVE];        /* [j]: its shadow ray's il_trace_visibility */
    float vis_k[LS_WAVE];          /* [k]: the shadow stream's answers */
    il_ray rays[LS_WAVE];
    il_hit hits[LS_WAVE];          /* [a] */
    il_surface surf[LS_WAVE];      /* [a] */
    uint32_t slot[LS_WAVE];        /* [j]: its row of u, for the drawing paths */
    uint32_t looking[LS_WAVE];     /* the paths with a pending lookup */
    il_ls_probe probe[LS_WAVE];    /* [k] of looking */
    il_ls_lookup_status status[LS_WAVE]; /* [k] of looking */
    il_vec3 Li[LS_WAVE];           /* [k] of looking */
    uint32_t tracing[LS_WAVE];     /* the k whose occlusion test is a ray */
    il_ray occ_rays[LS_WAVE];      /* their rays */
    bool occ_hit[LS_WAVE];
    il_vec2 u[LS_WAVE * LS_PAIRS];
    il_vec2 u_cos[LS_WAVE];
    il_vec3 cos_dir[LS_WAVE];
    il_diffuse_in diffuse_in[LS_WAVE];     /* [k] of drawing */
    il_diffuse_out diffuse_out[LS_WAVE];   /* [k] of drawing */
    il_diffuse_out *diffuse_ptr[LS_WAVE];
} ls_wave;

static void run_wave(const ls_method *m, ls_wave *w, uint32_t n, bool prefetch, ls_counts *cnt)
{
    const il_tracer *tr = m->scene->tracer;
    uint32_t num_active = n;
    for (uint32_t j = 0; j < n; j++)
        w->active[j] = j;
    for (bool camera = true; num_active > 0; camera = false) {
        for (uint32_t a = 0; a < num_active; a++) {
            w->stepped[a] = w->active[a];
            w->rays[a] = w->path[w->active[a]].ray;
        }
        if (camera)
            il_trace_closest_n_coherent(tr, w->rays, w->hits, num_active);
        else
            il_trace_closest_n(tr, w->rays, w->hits, num_active);
        il_wave_surfaces(m->scene, w->hits, num_active, prefetch, w->surf);

        /* The four pairs of every path that draws at this vertex, and the
         * cosine warps of their BSDF pairs, together. */
        uint32_t num_drawing = 0;
        for (uint32_t a = 0; a < num_active; a++) {
            uint32_t j = w->active[a];
            if (w->hits[a].mesh != IL_HIT_NONE && w->path[j].depth < m->set.max_depth) {
                w->slot[j] = num_drawing;
                w->diffuse_in[num_drawing].surf = &w->surf[a];
                w->drawing[num_drawing++] = j;
            }
        }
        il_sampler_2d_gather(w->smp, w->drawing, num_drawing, LS_PAIRS, w->u);
        for (uint32_t k = 0; k < num_drawing; k++)
            w->u_cos[k] = w->u[k * LS_PAIRS + 2];
        il_sample_cosine_hemisphere_n(w->u_cos, w->cos_dir, num_drawing);
        /* The Lambertian vertices' light samples and next directions,
         * eight at a time. */
        for (uint32_t k = 0; k < num_drawing; k++) {
            const ls_path *p = &w->path[w->drawing[k]];
            il_diffuse_in *in = &w->diffuse_in[k];
            in->wo = v3_neg(p->ray.dir);
            in->beta = p->beta;
            in->u_select = w->u[k * LS_PAIRS].x;
            in->u_lobe = w->u[k * LS_PAIRS].y;
            in->u_light = w->u[k * LS_PAIRS + 1];
            in->cos_dir = w->cos_dir[k];
            w->diffuse_ptr[k] = &w->diffuse_out[k];
        }
        il_diffuse_wave(m->scene, w->diffuse_in, w->diffuse_ptr, num_drawing, IL_DIFFUSE_NEE_PLAIN);

        uint32_t num_shadow = 0, num_looking = 0, still = 0;
        for (uint32_t a = 0; a < num_active; a++) {
            uint32_t j = w->active[a];
            ls_path *p = &w->path[j];
            bool hit = w->hits[a].mesh != IL_HIT_NONE;
            bool drawing = hit && p->depth < m->set.max_depth;
            uint32_t k = drawing ? w->slot[j] : 0;
            ls_step next = path_step(m, p, hit ? &w->hits[a] : NULL, &w->surf[a],
                                     drawing ? &w->u[k * LS_PAIRS] : NULL,
                                     drawing ? &w->cos_dir[k] : NULL, drawing ? &w->diffuse_out[k] : NULL,
                                     &w->smp[j], cnt);
            w->visible[j] = 1.0f;
            if (p->shadow) {
                w->shadowed[num_shadow] = j;
                w->rays[num_shadow++] = p->shadow_ray;
            }
            if (next == LS_GO) /* compaction in place: `still` never passes `a` */
                w->active[still++] = j;
            else if (next == LS_LOOKUP)
                w->looking[num_looking++] = j;
        }
        /* The lookups in three sweeps (shafts located, slots found, read),
         * each starting the next one's memory fetches, so that the cache
         * misses of the wave's lookups overlap. */
        for (uint32_t k = 0; k < num_looking; k++) {
            const ls_path *p = &w->path[w->looking[k]];
            il_ls_probe_at(m->ls, p->x, p->wi, &w->probe[k]);
        }
        for (uint32_t k = 0; k < num_looking; k++)
            il_ls_probe_slot(m->ls, m->test, &w->probe[k]);
        uint32_t num_tracing = 0;
        for (uint32_t k = 0; k < num_looking; k++) {
            ls_path *p = &w->path[w->looking[k]];
            w->Li[k] = v3s(0.0f);
            w->status[k] = il_ls_read_probe(m->ls, m->scene, &w->probe[k], p->x, p->wi, m->test,
                                            p->self_mesh, p->self_prim, &w->Li[k],
                                            &w->occ_rays[num_tracing]);
            if (w->status[k] == IL_LS_TRACE || w->status[k] == IL_LS_TRACE_EMPTY) {
                w->tracing[num_tracing++] = k;
                p->rays++;
            }
        }
        /* The occlusion tests of shafts without candidate lists, as one
         * stream. */
        if (num_tracing > 0) {
            il_trace_occluded_n(tr, w->occ_rays, w->occ_hit, num_tracing);
            for (uint32_t t = 0; t < num_tracing; t++)
                w->status[w->tracing[t]] = after_occlusion_ray(w->status[w->tracing[t]], w->occ_hit[t]);
        }
        for (uint32_t k = 0; k < num_looking; k++) {
            uint32_t j = w->looking[k];
            if (path_after_lookup(m, &w->path[j], w->status[k], w->Li[k], w->probe[k].coarse != NULL, cnt) ==
                LS_GO)
                w->active[still++] = j;
        }
        if (num_shadow > 0) {
            il_trace_visibility_n(tr, w->rays, w->vis_k, num_shadow);
            for (uint32_t k = 0; k < num_shadow; k++)
                w->visible[w->shadowed[k]] = w->vis_k[k];
        }
        for (uint32_t a = 0; a < num_active; a++)
            path_finish_vertex(&w->path[w->stepped[a]], w->visible[w->stepped[a]]);
        num_active = still;
    }
}

static void ls_tile(const void *method, const il_camera_pass_ctx *ctx, il_camera_tile *tile)
{
    ls_method *m = (ls_method *)method;
    ls_wave *w = tile->scratch;
    ls_counts cnt = {0};
    il_camera_wave_cursor cur = il_camera_wave_begin(tile);
    for (;;) {
        uint32_t n = il_camera_wave_fill(ctx, tile, &cur, LS_WAVE, w->smp, w->px, w->py, w->drawing,
                                         w->u, w->cos_dir);
        if (n == 0)
            break;
        for (uint32_t j = 0; j < n; j++)
            path_begin(&w->path[j], ctx->cam.position, w->cos_dir[j]);
        run_wave(m, w, n, m->prefetch, &cnt);
        for (uint32_t j = 0; j < n; j++) {
            tile->rays += w->path[j].rays;
            il_camera_tile_add(ctx, tile, w->px[j], w->py[j], w->path[j].L);
        }
    }
    atomic_fetch_add(&m->lookups, cnt.lookups);
    atomic_fetch_add(&m->hits, cnt.hits);
    atomic_fetch_add(&m->empty, cnt.empty);
    atomic_fetch_add(&m->occluded, cnt.occluded);
    atomic_fetch_add(&m->coarse, cnt.coarse);
    atomic_fetch_add(&m->outside, cnt.outside);
}

il_status il_ls_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                       il_render_stats *stats, il_error *err)
{
    il_render_stats local;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    il_ls_settings set;
    il_status s = il_ls_settings_resolve(desc->linespace, desc->max_depth, &set, err);
    if (s != IL_OK)
        return s;
    il_linespace_stats *st = &stats->linespace;
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    /* Split across processes, each injects the same paths: one stopping
     * alone would render its tiles from another Linespace. */
    if (il_distrib_on(desc->distrib))
        set.on_step = NULL;

    double t0 = omp_get_wtime();
    il_linespace ls;
    s = il_ls_build(scene, &set, threads, &ls, err);
    if (s != IL_OK)
        return s;
    double t1 = omp_get_wtime();
    il_ls_inject_result ir;
    s = il_ls_inject(scene, &set, desc->seed, threads, &ls, &ir, err);
    double t2 = omp_get_wtime();
    st->grid[0] = ls.res[0];
    st->grid[1] = ls.res[1];
    st->grid[2] = ls.res[2];
    for (int k = 0; k < 3; k++) {
        st->grid_min[k] = v3_get(ls.lo, k);
        st->grid_max[k] = v3_get(ls.hi, k);
    }
    st->interior = ls.partial;
    st->n = ls.n;
    st->voxels = ls.num_voxels;
    st->shafts = ls.num_stored;
    st->candidates = ls.num_cand;
    st->overflow_shafts = ls.num_overflow;
    st->memory_bytes = il_ls_memory(&ls);
    st->inject_rays = ir.injected;
    st->stopped = ir.stopped;
    st->injected_segments = ir.deposits;
    st->seconds_build = t1 - t0;
    st->seconds_inject = t2 - t1;
    if (s != IL_OK) {
        il_ls_free(&ls);
        return s;
    }

    ls_method mm;
    memset(&mm, 0, sizeof mm);
    ls_method *m = &mm;
    m->scene = scene;
    m->ls = &ls;
    m->set = set;
    m->prefetch = il_wave_wants_prefetch(scene);
    /* An empty entry is tested too when an occluded one traces on but an
     * empty one does not: what x sees there is not the shaft's light. */
    m->test = !set.occlusion_test                      ? IL_LS_TEST_NONE
              : set.fallback && !set.fallback_empty ? IL_LS_TEST_ALL
                                                    : IL_LS_TEST_LIT;
    m->blur_radius = set.blur * il_minf(ls.vsize.x, il_minf(ls.vsize.y, ls.vsize.z));
    il_camera_pass_result r = {0};
    s = il_camera_pass_tiles(scene, film, desc, ls_tile, m, sizeof(ls_wave), &r, err);
    st->seconds_sample = omp_get_wtime() - t2;
    st->lookups = atomic_load(&m->lookups);
    st->lookup_hits = atomic_load(&m->hits);
    st->lookup_empty = atomic_load(&m->empty);
    st->lookup_occluded = atomic_load(&m->occluded);
    st->lookup_coarse = atomic_load(&m->coarse);
    st->outside = atomic_load(&m->outside);
    il_ls_free(&ls);
    if (s != IL_OK)
        return s;
    stats->spp = r.spp;
    stats->rays = r.rays + ir.rays;
    stats->seconds = omp_get_wtime() - t0;
    stats->nonfinite_samples = r.nonfinite_samples;
    return IL_OK;
}
