#include "methods/camera_wave.h"

uint32_t il_camera_wave_fill(const il_camera_pass_ctx *ctx, const il_camera_tile *tile,
                             il_camera_wave_cursor *cur, uint32_t max, il_sampler *smp,
                             uint32_t *px, uint32_t *py, uint32_t *scratch, il_vec2 *u_scratch,
                             il_vec3 *dir)
{
    uint32_t n = 0, end = tile->first + tile->count;
    while (n < max && cur->y < tile->y1) {
        il_sampler_start(&smp[n], ctx->sampler, ctx->seed, (uint64_t)cur->y * ctx->width + cur->x,
                         cur->i);
        px[n] = cur->x;
        py[n] = cur->y;
        scratch[n] = n;
        n++;
        if (++cur->i == end) {
            cur->i = tile->first;
            if (++cur->x == tile->x1) {
                cur->x = tile->x0;
                cur->y++;
            }
        }
    }
    il_sampler_2d_gather(smp, scratch, n, 1, u_scratch);
    for (uint32_t j = 0; j < n; j++)
        dir[j] = il_camera_sample_dir(ctx, px[j], py[j], u_scratch[j]);
    return n;
}

/* Above this many bytes of triangle records (il_tri_geom) the surface reads
 * miss the caches and the prefetch passes pay; below, they only cost time. */
#define PREFETCH_BYTES (512u * 1024u)

bool il_wave_wants_prefetch(const il_scene *scene)
{
    uint64_t triangles = 0;
    for (uint32_t i = 0; i < scene->num_meshes; i++)
        triangles += scene->meshes[i].num_triangles;
    return triangles * sizeof(il_tri_geom) > PREFETCH_BYTES;
}

void il_wave_surfaces(const il_scene *s, const il_hit *hits, uint32_t n, bool prefetch,
                      il_surface *out)
{
    for (uint32_t a = 0; a < n && prefetch; a++) {
        const il_hit *h = &hits[a];
        if (h->mesh != IL_HIT_NONE && s->meshes[h->mesh].geom)
            __builtin_prefetch(&s->meshes[h->mesh].geom[h->prim]);
    }
    for (uint32_t a = 0; a < n && prefetch; a++) {
        const il_hit *h = &hits[a];
        if (h->mesh == IL_HIT_NONE)
            continue;
        const il_mesh *m = &s->meshes[h->mesh];
        if (!m->geom)
            continue;
        const uint32_t *v = m->geom[h->prim].v;
        for (int k = 0; k < 3; k++) {
            if (m->normals)
                __builtin_prefetch(&m->normals[v[k]]);
            if (m->uvs)
                __builtin_prefetch(&m->uvs[v[k]]);
        }
    }
    for (uint32_t a = 0; a < n; a++) {
        const il_hit *h = &hits[a];
        if (h->mesh != IL_HIT_NONE)
            il_scene_surface(s, h->mesh, h->prim, h->b1, h->b2, &out[a]);
    }
}
