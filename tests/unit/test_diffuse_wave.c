/* il_diffuse_wave (methods/diffuse_wave.c) against the scalar code it
 * stands for, bit for bit: for thousands of vertices found by random rays
 * in scenes with one- and two-sided triangle lamps, a ball lamp with
 * authored normals, a point, two directional (one with a disc) and three
 * spot lights (with and without a cos^n profile, one wider than a
 * hemisphere), a sky, Lambertian,
 * Phong (exponents 20 and 300) and mirror surfaces, its light sample must
 * equal il_pt_step_at's (under MIS) and il_direct_light_sample's (plain),
 * and its BSDF sample il_bsdf_sample_dir_cos's (a Phong surface's diffuse
 * lobe; its glossy lobe is left to the caller).  Vertices it must leave
 * to the caller (other materials; triangles of meshes with normals) must
 * keep their flags false.  On a CPU without AVX2 it takes nothing. */
#include <string.h>

#include "scene_build.h"

#include "core/rng.h"
#include "core/sampling.h"
#include "methods/diffuse_wave.h"
#include "scene/bsdf.h"
#include "scene/direct.h"
#include "scene/lights.h"
#include "scene/scene.h"
#include "trace/trace.h"

enum { N = 4096 };

static bool same_vec(il_vec3 a, il_vec3 b) { return memcmp(&a, &b, sizeof a) == 0; }
static bool same_ray(il_ray a, il_ray b)
{
    return same_vec(a.org, b.org) && same_vec(a.dir, b.dir) && a.tmin == b.tmin &&
           memcmp(&a.tmax, &b.tmax, sizeof a.tmax) == 0;
}

/* il_pt_step_at's next-event block under MIS, written out. */
static bool mis_light_sample(const il_scene *s, const il_surface *surf, il_vec3 wo, il_vec3 beta, float u_sel,
                             il_vec2 u, il_ray *shadow, il_vec3 *shadow_L)
{
    il_bsdf b;
    il_bsdf_init(&b, s, surf);
    il_light_sample ls;
    if (!il_light_sample_at(s, surf->p, u_sel, u, &ls) || !il_sides_agree(surf, wo, ls.wi))
        return false;
    float bsdf_pdf = 0.0f;
    il_vec3 f = il_bsdf_eval(&b, wo, ls.wi, &bsdf_pdf);
    float w = ls.delta ? 1.0f : il_power_heuristic(ls.pdf, bsdf_pdf);
    float cos_i = fabsf(v3_dot(ls.wi, b.frame.n));
    if (!(w > 0.0f && cos_i > 0.0f && !v3_is_zero(f)))
        return false;
    *shadow = isinf(ls.dist) ? (il_ray){.org = il_offset_origin(s->tracer, surf->p, surf->ng, ls.wi),
                                        .tmin = 0.0f, .dir = ls.wi, .tmax = INFINITY}
                             : il_shadow_ray(s->tracer, surf->p, surf->ng, ls.p, ls.n);
    *shadow_L = v3_scale(v3_mul(beta, v3_mul(f, ls.radiance)), cos_i * w / ls.pdf);
    return true;
}

/* il_direct_light_sample, as Linespace calls it. */
static bool plain_light_sample(const il_scene *s, const il_surface *surf, il_vec3 wo, float u_sel, il_vec2 u,
                               il_ray *shadow, il_vec3 *unblocked)
{
    il_bsdf b;
    il_bsdf_init(&b, s, surf);
    return il_direct_light_sample(s, surf, &b, wo, u_sel, u, shadow, unblocked);
}

/* Random vertices: rays from random points inside the scene's bounds. */
static uint32_t make_vertices(const il_scene *s, il_vec3 lo, il_vec3 hi, il_surface *surf,
                              il_diffuse_in *in)
{
    il_pcg32 rng = il_pcg32_seed(7, 11);
    uint32_t n = 0;
    for (uint32_t tries = 0; n < N && tries < 8 * N; tries++) {
        il_vec3 o = v3(lo.x + (hi.x - lo.x) * il_pcg32_float(&rng), lo.y + (hi.y - lo.y) * il_pcg32_float(&rng),
                       lo.z + (hi.z - lo.z) * il_pcg32_float(&rng));
        il_vec3 d = il_sample_uniform_sphere(v2(il_pcg32_float(&rng), il_pcg32_float(&rng)));
        il_ray r = {.org = o, .dir = d, .tmin = 0.0f, .tmax = INFINITY};
        il_hit hit;
        if (!il_trace_closest(s->tracer, &r, &hit))
            continue;
        il_scene_surface(s, hit.mesh, hit.prim, hit.b1, hit.b2, &surf[n]);
        il_vec2 u_bsdf = v2(il_pcg32_float(&rng), il_pcg32_float(&rng));
        in[n] = (il_diffuse_in){.surf = &surf[n], .wo = v3_neg(d),
                                .beta = v3(il_pcg32_float(&rng), il_pcg32_float(&rng), 0.5f),
                                .u_select = il_pcg32_float(&rng), .u_lobe = il_pcg32_float(&rng),
                                .u_light = v2(il_pcg32_float(&rng), il_pcg32_float(&rng)),
                                .cos_dir = il_sample_cosine_hemisphere(u_bsdf)};
        n++;
    }
    return n;
}

/* Checks every vertex of `s` in both modes; counts what the kernel took. */
static void check_scene(const il_scene *s, il_vec3 lo, il_vec3 hi, uint32_t *nee_taken, uint32_t *next_taken,
                        uint32_t *shadows)
{
    static il_surface surf[N];
    static il_diffuse_in in[N];
    static il_diffuse_out out[N];
    static il_diffuse_out *outp[N];
    uint32_t n = make_vertices(s, lo, hi, surf, in);
    CHECK(n == N);
    bool avx2 = __builtin_cpu_supports("avx2");
    for (uint32_t i = 0; i < n; i++)
        outp[i] = &out[i];
    for (int mode = IL_DIFFUSE_NEE_MIS; mode <= IL_DIFFUSE_NEE_PLAIN; mode++) {
        memset(out, 0xff, sizeof out); /* no flag may survive from before */
        il_diffuse_wave(s, in, outp, n, (il_diffuse_nee)mode);
        uint32_t bad_nee = 0, bad_next = 0, bad_flags = 0;
        for (uint32_t i = 0; i < n; i++) {
            const il_surface *sf = &surf[i];
            bool diffuse = sf->material->type == IL_MATERIAL_DIFFUSE;
            bool phong = sf->material->type == IL_MATERIAL_PHONG;
            il_bsdf bp;
            il_bsdf_init(&bp, s, sf);
            bool lobe_ours = diffuse || (phong && in[i].u_lobe < bp.diffuse_prob);
            const il_light *l = &s->lights[il_light_select(s, in[i].u_select)];
            bool takes = (l->kind == IL_LIGHTK_AREA && !s->meshes[l->mesh].normals) ||
                         l->kind == IL_LIGHTK_POINT || l->kind == IL_LIGHTK_SPOT ||
                         l->kind == IL_LIGHTK_DIRECTIONAL || l->kind == IL_LIGHTK_ENVIRONMENT;
            if (out[i].next_done != (avx2 && lobe_ours) || out[i].nee_done != (avx2 && (diffuse || phong) && takes)) {
                bad_flags++;
                continue;
            }
            if (out[i].nee_done) {
                (*nee_taken)++;
                il_ray ray = {0};
                il_vec3 L = v3s(0.0f);
                bool cast = mode == IL_DIFFUSE_NEE_MIS
                                ? mis_light_sample(s, sf, in[i].wo, in[i].beta, in[i].u_select, in[i].u_light, &ray, &L)
                                : plain_light_sample(s, sf, in[i].wo, in[i].u_select, in[i].u_light, &ray, &L);
                *shadows += cast;
                if (cast != out[i].shadow || (cast && (!same_ray(ray, out[i].shadow_ray) ||
                                                       !same_vec(L, out[i].shadow_L))))
                    bad_nee++;
            }
            if (out[i].next_done) {
                (*next_taken)++;
                il_bsdf b;
                il_bsdf_init(&b, s, sf);
                il_bsdf_sample bs;
                bool ok = il_bsdf_sample_dir_cos(&b, in[i].wo, in[i].u_lobe, v2(0.5f, 0.5f), &in[i].cos_dir, &bs) &&
                          il_sides_agree(sf, in[i].wo, bs.wi);
                il_ray next = {.org = il_offset_origin(s->tracer, sf->p, sf->ng, bs.wi), .tmin = 0.0f,
                               .dir = bs.wi, .tmax = INFINITY};
                if (ok != out[i].next_ok ||
                    (ok && (!same_vec(v3_mul(in[i].beta, bs.weight), out[i].next_beta) ||
                            memcmp(&bs.pdf, &out[i].next_pdf, sizeof bs.pdf) != 0 || !same_ray(next, out[i].next_ray))))
                    bad_next++;
            }
        }
        CHECK(bad_flags == 0);
        CHECK(bad_nee == 0);
        CHECK(bad_next == 0);
        if (bad_flags + bad_nee + bad_next)
            fprintf(stderr, "mode %d: %u wrong flags, %u wrong light samples, %u wrong BSDF samples\n", mode,
                    bad_flags, bad_nee, bad_next);
    }
}

/* A room of Lambertian walls, a Phong floor and wall, and a mirror, lit by a
 * one-sided and a two-sided quad lamp, a ball lamp (authored normals), a
 * point light, the sun, three spot lights and a sky. */
static il_scene *mixed_room(void)
{
    il_scene *s = new_scene();
    uint32_t white = add_material(s, (il_material_desc){.diffuse = v3(0.7f, 0.7f, 0.7f)});
    uint32_t red = add_material(s, (il_material_desc){.diffuse = v3(0.6f, 0.1f, 0.1f)});
    uint32_t phong = add_material(s, (il_material_desc){.type = IL_MATERIAL_PHONG, .diffuse = v3s(0.3f),
                                                         .specular = v3s(0.4f), .exponent = 20.0f});
    uint32_t shiny = add_material(s, (il_material_desc){.type = IL_MATERIAL_PHONG, .diffuse = v3(0.6f, 0.1f, 0.1f),
                                                         .specular = v3(0.5f, 0.6f, 0.6f), .exponent = 300.0f});
    uint32_t mirror = add_material(s, (il_material_desc){.type = IL_MATERIAL_MIRROR, .specular = v3s(0.9f)});
    uint32_t lamp = add_material(s, (il_material_desc){.emission = v3(5, 5, 4)});
    uint32_t lamp2 = add_material(s, (il_material_desc){.emission = v3(2, 3, 4), .two_sided = true});
    add_floor(s, 0.0f, 2.0f, phong);
    add_quad(s, v3(0, 2, 0), v3(2, 0, 0), v3(0, 0, -2), white);   /* ceiling, facing down */
    add_quad(s, v3(-2, 1, 0), v3(0, 0, 2), v3(0, 1, 0), shiny);   /* left wall */
    add_quad(s, v3(2, 1, 0), v3(0, 1, 0), v3(0, 0, 2), white);
    add_quad(s, v3(0, 1, -2), v3(2, 0, 0), v3(0, 1, 0), red);
    add_quad(s, v3(0.5f, 0.6f, 0.5f), v3(0.3f, 0, 0), v3(0, 0.3f, 0), mirror);
    add_quad(s, v3(0, 1.95f, 0), v3(0.3f, 0, 0), v3(0, 0, 0.3f), lamp);
    add_quad(s, v3(-1, 1, -1), v3(0.2f, 0, 0), v3(0, 0.2f, 0.1f), lamp2);
    add_ball(s, v3(1, 0.4f, -1), 0.2f, lamp);
    const il_light_desc lights[] = {
        {.type = IL_LIGHT_POINT, .position = {0.5f, 1.5f, 1}, .intensity = {2, 2, 2}},
        {.type = IL_LIGHT_DIRECTIONAL, .direction = {0.3f, -1, 0.2f}, .intensity = {1, 0.9f, 0.8f}},
        {.type = IL_LIGHT_SPOT, .position = {-1, 1.8f, 1}, .direction = {0.2f, -1, -0.3f},
         .intensity = {3, 3, 3}, .spot_angle = 40.0f, .spot_exponent = 4.0f},
        {.type = IL_LIGHT_SPOT, .position = {1.2f, 1.7f, -0.5f}, .direction = {-0.4f, -1, 0.1f},
         .intensity = {2, 1, 1}, .spot_angle = 25.0f},
        {.type = IL_LIGHT_SPOT, .position = {0, 1.0f, 0.5f}, .direction = {0, 0, -1},
         .intensity = {1, 1, 2}, .spot_angle = 120.0f, .spot_exponent = 2.0f},
        {.type = IL_LIGHT_DIRECTIONAL, .direction = {-0.2f, -1, -0.4f}, .intensity = {0.8f, 0.8f, 1},
         .diameter = 6.0f}};
    for (int i = 0; i < 6; i++)
        CHECK_OK(il_scene_add_light(s, &lights[i], &g_err), &g_err);
    il_environment_desc sky = {.radiance = v3(0.2f, 0.25f, 0.3f)}; /* seen through the open front */
    CHECK_OK(il_scene_set_environment(s, &sky, &g_err), &g_err);
    set_camera(s, v3(0, 1, 3.5f), v3(0, 1, 0), v3(0, 1, 0), 55.0f);
    commit(s);
    return s;
}

int main(void)
{
    uint32_t nee = 0, next = 0, shadows = 0;
    il_scene *room = mixed_room();
    check_scene(room, v3(-1.9f, 0.1f, -1.9f), v3(1.9f, 1.9f, 1.9f), &nee, &next, &shadows);
    il_scene_release(room);
    il_scene *cornell = load_committed("cornell");
    if (cornell) {
        check_scene(cornell, v3(0.05f, 0.05f, 0.05f), v3(0.5f, 0.5f, 0.5f), &nee, &next, &shadows);
        il_scene_release(cornell);
    }
    printf("light samples taken %u (shadow rays %u), BSDF samples taken %u\n", nee, shadows, next);
    /* The comparisons above must have had something to compare. */
    if (__builtin_cpu_supports("avx2"))
        CHECK(nee > 4000 && next > 8000 && shadows > 2000);
    return check_report();
}
