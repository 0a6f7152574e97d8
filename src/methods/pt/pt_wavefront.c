/* The path tracer's camera pass, wavefront style: the paths of a tile
 * advance together one vertex at a time, and each step's rays go to Embree
 * as one stream (il_trace_closest_n, then il_trace_visibility_n for the
 * shadow rays), in the manner of Laine, Karras & Aila 2013, "Megakernels
 * Considered Harmful: Wavefront Path Tracing on GPUs", here on a CPU: the
 * stream calls are cheaper per ray, and tracing and shading each run as one
 * tight loop, which keeps Embree's and the shader's code and branch history
 * warm.
 *
 * Every path runs exactly the estimator of il_pt_radiance (il_pt_step), with
 * the same sample numbers and the same order of additions to its radiance,
 * and the film receives a pixel's samples in increasing index: the shared
 * camera pass (methods/camera_pass.c) runs the tiles, passes, progress
 * reports, time limit and treatment of NaN samples, and this file only the
 * work of a tile (il_camera_pass_tiles), so the film is bit-identical to
 * il_camera_pass with il_pt_radiance, and the same with 1 or N threads. */
#include "core/sampling.h"
#include "methods/camera_pass.h"
#include "methods/camera_wave.h"
#include "methods/pt/pt.h"

typedef struct pt_method {
    const il_scene *scene;
    uint32_t max_depth;
    il_pt_strategy strategy;
    bool prefetch;         /* the triangle records outgrow the caches (il_wave_wants_prefetch) */
} pt_method;

/* One wave: up to IL_PT_WAVE paths with their samplers and pixels, the gather
 * buffers for the stream calls, and what is computed for all paths of a
 * vertex before any is shaded (surfaces, samples, cosine directions); one
 * per thread (about 140 KB), the camera pass's scratch memory.  Arrays
 * indexed by path are [j], by position in the active list [a]. */
typedef struct pt_wave {
    il_pt_state st[IL_PT_WAVE];
    il_sampler smp[IL_PT_WAVE];
    uint32_t px[IL_PT_WAVE], py[IL_PT_WAVE];
    uint32_t active[IL_PT_WAVE], shadowed[IL_PT_WAVE];
    il_ray rays[IL_PT_WAVE];
    il_hit hits[IL_PT_WAVE];          /* [a] */
    il_surface surf[IL_PT_WAVE];      /* [a] */
    float visible[IL_PT_WAVE];
    il_pt_drawn drawn[IL_PT_WAVE];    /* [a], for the paths that draw samples */
    uint32_t list[2][IL_PT_WAVE];     /* paths drawing 3 pairs, and 4 (with the roulette) */
    uint32_t slot[2][IL_PT_WAVE];     /* their [a] */
    il_vec2 u[IL_PT_WAVE * 4];        /* il_sampler_2d_gather's output */
    il_vec2 u_cos[IL_PT_WAVE];        /* the BSDF pairs, warped together */
    il_vec3 cos_dir[IL_PT_WAVE];
    il_diffuse_in diffuse_in[IL_PT_WAVE];      /* the drawing paths' vertices, for */
    il_diffuse_out *diffuse_out[IL_PT_WAVE];   /* il_diffuse_wave */
} pt_wave;

/* The samples of every path that draws them at this vertex (a hit below
 * the maximum depth: see il_pt_step), all drawn together: three pairs, and
 * with a Sobol sampler from the fourth bounce on a fourth whose first member
 * is the roulette number il_sampler_1d would give (a PCG sampler's 1D draw
 * takes one number, not a pair, so there it stays in il_pt_step_at).  Then
 * the cosine-weighted directions of the BSDF pairs, together, and last the
 * light samples and next rays of the Lambertian and Phong vertices, eight at a time
 * (il_diffuse_wave), which il_pt_step_at then only applies. */
static void wave_samples(const pt_method *pm, pt_wave *w, uint32_t num)
{
    uint32_t n[2] = {0, 0};
    for (uint32_t a = 0; a < num; a++) {
        uint32_t j = w->active[a];
        if (w->hits[a].mesh == IL_HIT_NONE || w->st[j].depth >= pm->max_depth)
            continue;
        int r = w->st[j].depth >= 3 && w->smp[j].type == IL_SAMPLER_SOBOL;
        w->list[r][n[r]] = j;
        w->slot[r][n[r]++] = a;
    }
    uint32_t num_cos = 0;
    for (int r = 0; r < 2; r++) {
        uint32_t pairs = 3u + (uint32_t)r;
        il_sampler_2d_gather(w->smp, w->list[r], n[r], pairs, w->u);
        for (uint32_t k = 0; k < n[r]; k++) {
            il_pt_drawn *d = &w->drawn[w->slot[r][k]];
            for (uint32_t p = 0; p < pairs; p++)
                d->u[p] = w->u[k * pairs + p];
            d->roulette = r == 1;
            w->u_cos[num_cos++] = d->u[2];
        }
    }
    il_sample_cosine_hemisphere_n(w->u_cos, w->cos_dir, num_cos);
    num_cos = 0;
    for (int r = 0; r < 2; r++)
        for (uint32_t k = 0; k < n[r]; k++)
            w->drawn[w->slot[r][k]].cos_dir = w->cos_dir[num_cos++];
    uint32_t num_drawn = 0;
    for (int r = 0; r < 2; r++)
        for (uint32_t k = 0; k < n[r]; k++) {
            uint32_t j = w->list[r][k], a = w->slot[r][k];
            il_pt_drawn *d = &w->drawn[a];
            w->diffuse_in[num_drawn] = (il_diffuse_in){
                .surf = &w->surf[a], .wo = v3_neg(w->st[j].ray.dir), .beta = w->st[j].beta,
                .u_select = d->u[0].x, .u_lobe = d->u[0].y, .u_light = d->u[1], .cos_dir = d->cos_dir};
            w->diffuse_out[num_drawn++] = &d->diffuse;
        }
    if (pm->strategy == IL_PT_MIS)
        il_diffuse_wave(pm->scene, w->diffuse_in, w->diffuse_out, num_drawn, IL_DIFFUSE_NEE_MIS);
    else /* the other strategies are for tests: one vertex at a time */
        for (uint32_t k = 0; k < num_drawn; k++)
            w->diffuse_out[k]->nee_done = w->diffuse_out[k]->next_done = false;
}

/* Runs paths 0..n-1 of the wave to their ends.  With `at_sensors`, path j
 * starts at the vertex w->surf[j] with hit w->hits[j] (a sensor:
 * il_pt_sensor_begin) instead of tracing its ray. */
static void run_wave(const pt_method *pm, pt_wave *w, uint32_t n, bool at_sensors)
{
    const il_tracer *tr = pm->scene->tracer;
    uint32_t num_active = n;
    for (uint32_t j = 0; j < n; j++)
        w->active[j] = j;
    for (bool camera = true; num_active > 0; camera = false) {
        if (!(camera && at_sensors)) { /* a sensor path's first vertex is set */
            for (uint32_t a = 0; a < num_active; a++)
                w->rays[a] = w->st[w->active[a]].ray;
            if (camera) /* a tile's camera rays: neighbours, alike */
                il_trace_closest_n_coherent(tr, w->rays, w->hits, num_active);
            else
                il_trace_closest_n(tr, w->rays, w->hits, num_active);
            il_wave_surfaces(pm->scene, w->hits, num_active, pm->prefetch, w->surf);
        }
        wave_samples(pm, w, num_active);

        uint32_t num_shadow = 0, still = 0;
        for (uint32_t a = 0; a < num_active; a++) {
            uint32_t j = w->active[a];
            bool hit = w->hits[a].mesh != IL_HIT_NONE;
            bool drawing = hit && w->st[j].depth < pm->max_depth;
            bool more = il_pt_step_at(pm->scene, &w->st[j], hit ? &w->hits[a] : NULL,
                                      hit ? &w->surf[a] : NULL, drawing ? &w->drawn[a] : NULL,
                                      &w->smp[j], pm->max_depth, pm->strategy);
            if (w->st[j].shadow) {
                w->shadowed[num_shadow] = j;
                w->rays[num_shadow++] = w->st[j].shadow_ray;
            }
            /* Compaction in place: `still` never passes `a`. */
            if (more)
                w->active[still++] = j;
        }
        if (num_shadow > 0) {
            il_trace_visibility_n(tr, w->rays, w->visible, num_shadow);
            for (uint32_t k = 0; k < num_shadow; k++)
                il_pt_shadow_result(&w->st[w->shadowed[k]], w->visible[k]);
        }
        num_active = still;
    }
}

/* The tile's samples in waves taken in the order the camera pass wants them
 * (pixel by pixel, samples in increasing index: il_camera_wave_fill), and
 * added to the film in that order. */
static void render_tile(const void *method, const il_camera_pass_ctx *ctx, il_camera_tile *tile)
{
    const pt_method *pm = method;
    pt_wave *w = tile->scratch;
    il_camera_wave_cursor cur = il_camera_wave_begin(tile);
    for (;;) {
        uint32_t n = il_camera_wave_fill(ctx, tile, &cur, IL_PT_WAVE, w->smp, w->px, w->py, w->list[0],
                                         w->u, w->cos_dir);
        if (n == 0)
            break;
        for (uint32_t j = 0; j < n; j++)
            il_pt_begin(&w->st[j], ctx->cam.position, w->cos_dir[j]);
        run_wave(pm, w, n, false);
        for (uint32_t j = 0; j < n; j++) {
            tile->rays += w->st[j].rays;
            il_camera_tile_add(ctx, tile, w->px[j], w->py[j], w->st[j].L);
        }
    }
}

il_status il_pt_wavefront_pass(const il_scene *scene, il_film *film, const il_render_desc *desc,
                               uint32_t max_depth, il_pt_strategy strategy,
                               il_camera_pass_result *out, il_error *err)
{
    pt_method pm = {.scene = scene, .max_depth = max_depth, .strategy = strategy,
                    .prefetch = il_wave_wants_prefetch(scene)};
    return il_camera_pass_tiles(scene, film, desc, render_tile, &pm, sizeof(pt_wave), out, err);
}

/* The tile work alone, for a caller that runs its own tiles
 * (methods/render_region.c, the distributed render). */
size_t il_pt_wavefront_scratch_bytes(void) { return sizeof(pt_wave); }

void il_pt_wavefront_tile(const il_scene *scene, uint32_t max_depth, il_pt_strategy strategy,
                          const il_camera_pass_ctx *ctx, il_camera_tile *tile)
{
    pt_method pm = {.scene = scene, .max_depth = max_depth, .strategy = strategy,
                    .prefetch = il_wave_wants_prefetch(scene)};
    render_tile(&pm, ctx, tile);
}

void il_pt_sensor_wave(const il_scene *scene, uint32_t max_depth, bool prefetch, void *scratch,
                       const il_vec3 *p, const il_vec3 *n, const il_sampler *smp, uint32_t count,
                       il_vec3 *out, uint64_t *rays)
{
    pt_method pm = {.scene = scene, .max_depth = max_depth, .strategy = IL_PT_MIS, .prefetch = prefetch};
    pt_wave *w = scratch;
    for (uint32_t j = 0; j < count; j++) {
        il_pt_sensor_begin(&w->st[j], p[j], n[j], &w->surf[j], &w->hits[j]);
        w->smp[j] = smp[j];
    }
    run_wave(&pm, w, count, true);
    for (uint32_t j = 0; j < count; j++) {
        *rays += w->st[j].rays;
        out[j] = v3_scale(w->st[j].L, IL_PI);
    }
}
