/* Radiosity output: per-vertex averaging, the camera pass over the meshed
 * scene (Gouraud interpolation, mirrors, Phong lobe, background, back faces,
 * determinism) and the adaptive-split marking.
 *
 * The meshes here are built by hand (a grid of quad patches per surface, the
 * layout il_patch_mesh_build produces) so every vertex value is known. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "methods/radiosity/rad.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/trace.h"

#define MAXV 512
#define MAXP 256
#define MAXT 512

/* A hand-built il_patch_mesh with fixed capacity. */
typedef struct tmesh {
    il_patch_mesh m;
} tmesh;

static void tmesh_init(tmesh *t)
{
    memset(t, 0, sizeof *t);
    /* One vertex of padding for Embree (see il_tracer_create_triangles). */
    t->m.positions = calloc(MAXV + 1, sizeof(il_vec3));
    t->m.vertex_surface = calloc(MAXV, sizeof(uint32_t));
    t->m.patches = calloc(MAXP, sizeof(il_patch));
    t->m.surfaces = calloc(64, sizeof(il_patch_surface));
    t->m.tri_indices = calloc(3 * MAXT, sizeof(uint32_t));
    t->m.tri_patch = calloc(MAXT, sizeof(uint32_t));
    t->m.tri_src_mesh = calloc(MAXT, sizeof(uint32_t));
    t->m.tri_src_prim = calloc(MAXT, sizeof(uint32_t));
}

static void tmesh_free(tmesh *t)
{
    il_tracer_release(t->m.tracer);
    free(t->m.positions);
    free(t->m.vertex_surface);
    free(t->m.patches);
    free(t->m.surfaces);
    free(t->m.tri_indices);
    free(t->m.tri_patch);
    free(t->m.tri_src_mesh);
    free(t->m.tri_src_prim);
}

/* Adds a surface: the parallelogram origin + a U + b V, (a, b) in [0,1]^2,
 * front towards U x V, cut at the fractions xs[0..nx] (0 .. 1) along U and
 * ys[0..ny] along V.  It becomes one scene mesh (2 triangles per cell) and,
 * when `patched`, one quad patch per cell; else its triangles get no patch
 * (mirror/glass).  Returns the index of the first patch. */
static uint32_t add_grid(il_scene *scene, tmesh *t, il_vec3 origin, il_vec3 U, il_vec3 V,
                         const float *xs, uint32_t nx, const float *ys, uint32_t ny,
                         uint32_t material, bool patched)
{
    il_error err = {0};
    il_patch_mesh *m = &t->m;
    uint32_t v0 = m->num_vertices, first_patch = m->num_patches;
    uint32_t surface = m->num_surfaces++;
    m->surfaces[surface] = (il_patch_surface){.mesh = scene->num_meshes, .material = material,
                                            .diffuse = patched};
    float pos[3 * 64];
    uint32_t idx[3 * 128];
    for (uint32_t j = 0; j <= ny; j++)
        for (uint32_t i = 0; i <= nx; i++) {
            il_vec3 p = v3_add(origin, v3_add(v3_scale(U, xs[i]), v3_scale(V, ys[j])));
            uint32_t k = j * (nx + 1) + i;
            pos[3 * k] = p.x, pos[3 * k + 1] = p.y, pos[3 * k + 2] = p.z;
            m->positions[v0 + k] = p;
            m->vertex_surface[v0 + k] = surface;
        }
    m->num_vertices += (nx + 1) * (ny + 1);
    il_vec3 n = v3_cross(U, V);
    float full_area = v3_length(n);
    n = v3_normalize(n);
    uint32_t ntri = 0;
    for (uint32_t j = 0; j < ny; j++)
        for (uint32_t i = 0; i < nx; i++) {
            uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
            uint32_t quad[4] = {a, b, c, d};
            uint32_t tris[2][3] = {{a, b, c}, {a, c, d}};
            uint32_t patch = IL_NO_PATCH;
            if (patched) {
                patch = m->num_patches++;
                il_patch *p = &m->patches[patch];
                p->num_corners = 4;
                p->center = v3s(0.0f);
                for (int c4 = 0; c4 < 4; c4++) {
                    p->v[c4] = v0 + quad[c4];
                    p->center = v3_fma(p->center, m->positions[v0 + quad[c4]], 0.25f);
                }
                p->normal = n;
                p->area = full_area * (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]);
                p->surface = surface;
                p->rho = v3s(0.5f);
            }
            for (int k = 0; k < 2; k++) {
                uint32_t tt = m->num_tris++;
                for (int c3 = 0; c3 < 3; c3++) {
                    m->tri_indices[3 * tt + c3] = v0 + tris[k][c3];
                    idx[3 * ntri + c3] = tris[k][c3];
                }
                m->tri_patch[tt] = patch;
                m->tri_src_mesh[tt] = scene->num_meshes;
                m->tri_src_prim[tt] = ntri++;
            }
        }
    CHECK_OK(il_scene_add_mesh(scene, &(il_mesh_desc){.num_vertices = (nx + 1) * (ny + 1),
                                                       .num_triangles = ntri, .positions = pos,
                                                       .indices = idx, .material = material},
                               &err),
             &err);
    return first_patch;
}

static const float UNIT2[] = {0.0f, 0.5f, 1.0f};
static const float UNIT1[] = {0.0f, 1.0f};

static void tmesh_commit(il_scene *scene, tmesh *t)
{
    il_error err = {0};
    CHECK_OK(il_scene_commit(scene, &err), &err);
    CHECK_OK(il_tracer_create_triangles(t->m.positions, t->m.num_vertices, t->m.tri_indices,
                                        t->m.num_tris, &t->m.tracer, &err),
             &err);
}

static il_scene *new_scene(il_vec3 env, il_vec3 cam_pos, il_vec3 target)
{
    il_error err = {0};
    il_scene *scene = NULL;
    CHECK_OK(il_scene_create(&scene, &err), &err);
    CHECK_OK(il_scene_set_environment(scene, &(il_environment_desc){.radiance = env}, &err), &err);
    CHECK_OK(il_scene_set_camera(scene, &(il_camera_desc){.position = cam_pos, .target = target,
                                                          .fov_y = 40.0f},
                                 &err),
             &err);
    return scene;
}

/* ---------------------------------------------------------- vertex averaging */

static void test_vertex_average(void)
{
    il_scene *scene = new_scene(v3s(1.0f), v3(0, 0, 3), v3s(0.0f));
    tmesh t;
    tmesh_init(&t);
    /* A 2x2 quad of equal patches 1,2,3,4; then a second surface cut
     * unequally (widths 0.25 and 0.75 of 2 m, heights 0.5/0.5); then a
     * mirror whose vertices no patch uses. */
    uint32_t p0 = add_grid(scene, &t, v3(-1, -1, 0), v3(2, 0, 0), v3(0, 2, 0), UNIT2, 2, UNIT2, 2, 0, true);
    static const float xs[] = {0.0f, 0.25f, 1.0f};
    uint32_t p1 = add_grid(scene, &t, v3(-1, -1, -1), v3(2, 0, 0), v3(0, 2, 0), xs, 2, UNIT2, 2, 0, true);
    uint32_t v_mirror = t.m.num_vertices;
    add_grid(scene, &t, v3(-1, -1, -2), v3(2, 0, 0), v3(0, 2, 0), UNIT1, 1, UNIT1, 1, 0, false);
    CHECK(t.m.num_patches == 8);

    il_vec3 rad[8];
    for (uint32_t i = 0; i < 4; i++) {
        rad[p0 + i] = v3((float)(i + 1), 2.0f * (float)(i + 1), 0.5f);
        rad[p1 + i] = v3((float)(i + 1), 0.0f, 1.0f);
    }
    il_vec3 out[MAXV];
    il_patch_vertex_radiance(&t.m, rad, out);

    /* Grid 3x3, vertex k = j*3 + i; patches 0:(0,0) 1:(1,0) 2:(0,1) 3:(1,1). */
    CHECK_NEAR(out[4].x, 2.5f, 1e-6);          /* centre: (1+2+3+4)/4 */
    CHECK_NEAR(out[4].y, 5.0f, 1e-6);
    CHECK_NEAR(out[4].z, 0.5f, 1e-6);
    CHECK_NEAR(out[0].x, 1.0f, 1e-6);          /* corners: their own patch */
    CHECK_NEAR(out[2].x, 2.0f, 1e-6);
    CHECK_NEAR(out[6].x, 3.0f, 1e-6);
    CHECK_NEAR(out[8].x, 4.0f, 1e-6);
    CHECK_NEAR(out[8].y, 8.0f, 1e-6);
    CHECK_NEAR(out[1].x, 1.5f, 1e-6);          /* edge midpoints: two patches */
    CHECK_NEAR(out[3].x, 2.0f, 1e-6);          /* patches 0 and 2 */
    CHECK_NEAR(out[5].x, 3.0f, 1e-6);          /* patches 1 and 3 */

    /* Unequal areas: patches 0 and 2 are 0.5 x 1 m, patches 1 and 3 1.5 x 1 m. */
    uint32_t c = 9 + 4;
    double a_small = 0.5, a_big = 1.5;
    CHECK_NEAR(t.m.patches[p1].area, a_small, 1e-6);
    CHECK_NEAR(t.m.patches[p1 + 1].area, a_big, 1e-6);
    CHECK_NEAR(out[c].x, (1 * a_small + 2 * a_big + 3 * a_small + 4 * a_big) / (2 * (a_small + a_big)), 1e-6);
    CHECK_NEAR(out[c].z, 1.0f, 1e-6);
    CHECK_NEAR(out[9 + 1].x, (1 * a_small + 2 * a_big) / (a_small + a_big), 1e-6);
    CHECK_NEAR(out[9 + 0].x, 1.0f, 1e-6);
    /* The surfaces share no vertex, so the first grid's values did not
     * leak into the second (its corner 9 would otherwise not be 1). */
    CHECK_NEAR(out[9 + 8].x, 4.0f, 1e-6);

    /* Mirror vertices: zero. */
    for (uint32_t v = v_mirror; v < t.m.num_vertices; v++)
        CHECK(v3_is_zero(out[v]));

    tmesh_free(&t);
    il_scene_release(scene);
}

/* ------------------------------------------------------------------- render */

/* Where the centre ray of pixel (x, y) meets the plane z = zp. */
static il_vec3 pixel_on_plane(const il_scene *scene, uint32_t w, uint32_t h, float fx, float fy, float zp)
{
    il_camera cam;
    il_camera_init(&cam, &scene->camera.desc, w, h);
    il_vec3 d = il_camera_ray_dir(&cam, fx, fy);
    float t = (zp - cam.position.z) / d.z;
    return v3_fma(cam.position, d, t);
}

static il_image render(const il_scene *scene, const tmesh *t, const il_vec3 *vrad, uint32_t w,
                       uint32_t h, il_render_desc rd, il_render_stats *stats)
{
    il_error err = {0};
    il_film *film = NULL;
    il_image img = {0};
    CHECK_OK(il_film_create(w, h, &film, &err), &err);
    CHECK_OK(il_patch_render_film(scene, &t->m, vrad, film, &rd, stats, &err), &err);
    CHECK_OK(il_film_resolve(film, &img, &err), &err);
    il_film_release(film);
    return img;
}

static il_vec3 pixel(const il_image *img, uint32_t x, uint32_t y)
{
    const float *p = img->rgb + 3 * ((size_t)y * img->width + x);
    return v3(p[0], p[1], p[2]);
}

#define W 32
#define H 32

static void test_render_constant_and_background(void)
{
    il_vec3 env = v3(0.1f, 0.2f, 0.3f);
    il_scene *scene = new_scene(env, v3(0, 0, 3), v3s(0.0f));
    tmesh t;
    tmesh_init(&t);
    add_grid(scene, &t, v3(-0.8f, -0.8f, 0), v3(1.6f, 0, 0), v3(0, 1.6f, 0), UNIT2, 2, UNIT2, 2, 0, true);
    tmesh_commit(scene, &t);
    il_vec3 vrad[MAXV];
    for (uint32_t v = 0; v < t.m.num_vertices; v++)
        vrad[v] = v3(0.7f, 0.7f, 0.7f);
    il_render_stats stats = {0};
    il_image img = render(scene, &t, vrad, W, H, (il_render_desc){.spp = 4, .seed = 7}, &stats);
    CHECK(stats.spp == 4);
    CHECK(stats.rays == (uint64_t)W * H * 4);   /* camera rays only: nothing bounces */

    int inside = 0, outside = 0;
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            /* Classify by the whole pixel footprint (box filter): all four
             * corners on the quad, or all off it. */
            int on = 0;
            for (int c = 0; c < 4; c++) {
                il_vec3 p = pixel_on_plane(scene, W, H, (float)(x + (c & 1)), (float)(y + (c >> 1)), 0);
                on += fabsf(p.x) < 0.8f && fabsf(p.y) < 0.8f;
            }
            il_vec3 L = pixel(&img, x, y);
            if (on == 4) {
                inside++;
                CHECK_NEAR(L.x, 0.7f, 1e-6);
                CHECK_NEAR(L.y, 0.7f, 1e-6);
                CHECK_NEAR(L.z, 0.7f, 1e-6);
            } else if (on == 0) {
                outside++;
                CHECK_NEAR(L.x, env.x, 1e-7);
                CHECK_NEAR(L.y, env.y, 1e-7);
                CHECK_NEAR(L.z, env.z, 1e-7);
            }
        }
    CHECK(inside > 100);
    CHECK(outside > 100);
    il_image_free(&img);
    tmesh_free(&t);
    il_scene_release(scene);
}

static void test_render_back_side(void)
{
    il_scene *scene = new_scene(v3s(0.4f), v3(0, 0, 3), v3s(0.0f));
    tmesh t;
    tmesh_init(&t);
    /* U x V = -z: the quad faces away from the camera. */
    add_grid(scene, &t, v3(-0.8f, -0.8f, 0), v3(0, 1.6f, 0), v3(1.6f, 0, 0), UNIT1, 1, UNIT1, 1, 0, true);
    tmesh_commit(scene, &t);
    il_vec3 vrad[MAXV];
    for (uint32_t v = 0; v < t.m.num_vertices; v++)
        vrad[v] = v3s(0.7f);
    il_image img = render(scene, &t, vrad, W, H, (il_render_desc){.spp = 2}, NULL);
    il_vec3 c = pixel(&img, W / 2, H / 2), corner = pixel(&img, 0, 0);
    CHECK(v3_is_zero(c));
    CHECK_NEAR(corner.x, 0.4f, 1e-7);
    il_image_free(&img);
    tmesh_free(&t);
    il_scene_release(scene);
}

static void test_render_gradient(void)
{
    il_scene *scene = new_scene(v3s(0.1f), v3(0, 0, 3), v3s(0.0f));
    tmesh t;
    tmesh_init(&t);
    add_grid(scene, &t, v3(-1, -1, 0), v3(2, 0, 0), v3(0, 2, 0), UNIT2, 2, UNIT2, 2, 0, true);
    tmesh_commit(scene, &t);
    /* A linear function of position: Gouraud interpolation reproduces it
     * exactly, and the plane is parallel to the film, so a pixel's mean
     * over its (box) footprint is its value at the pixel centre. */
    il_vec3 vrad[MAXV];
    for (uint32_t v = 0; v < t.m.num_vertices; v++) {
        il_vec3 p = t.m.positions[v];
        vrad[v] = v3(0.5f + 0.25f * p.x, 0.5f - 0.2f * p.y, 0.3f + 0.1f * p.x + 0.1f * p.y);
    }
    il_image img = render(scene, &t, vrad, W, H, (il_render_desc){.spp = 64, .seed = 3}, NULL);
    const uint32_t px[][2] = {{10, 12}, {20, 9}, {16, 16}, {7, 24}};
    for (size_t k = 0; k < sizeof px / sizeof px[0]; k++) {
        il_vec3 p = pixel_on_plane(scene, W, H, (float)px[k][0] + 0.5f, (float)px[k][1] + 0.5f, 0);
        CHECK(fabsf(p.x) < 0.9f && fabsf(p.y) < 0.9f);
        il_vec3 L = pixel(&img, px[k][0], px[k][1]);
        /* One pixel spans 0.034 m: 0.0085 of the x gradient.  64 stratified
         * samples put the mean offset within a small fraction of that. */
        CHECK_NEAR(L.x, 0.5f + 0.25f * p.x, 2e-4);
        CHECK_NEAR(L.y, 0.5f - 0.2f * p.y, 2e-4);
        CHECK_NEAR(L.z, 0.3f + 0.1f * p.x + 0.1f * p.y, 2e-4);
    }
    il_image_free(&img);
    tmesh_free(&t);
    il_scene_release(scene);
}

/* A mirror at z = 0 facing the camera at z = 3; behind the camera a patch
 * at z = 5 facing the mirror.  Returns the scene; fills t. */
static il_scene *mirror_scene(tmesh *t, il_vec3 tint)
{
    il_error err = {0};
    il_scene *scene = new_scene(v3(0.05f, 0.1f, 0.15f), v3(0, 0, 3), v3s(0.0f));
    tmesh_init(t);
    uint32_t mirror;
    CHECK_OK(il_scene_add_material(scene, &(il_material_desc){.type = IL_MATERIAL_MIRROR, .specular = tint},
                                   &mirror, &err),
             &err);
    add_grid(scene, t, v3(-1, -1, 0), v3(2, 0, 0), v3(0, 2, 0), UNIT1, 1, UNIT1, 1, mirror, false);
    /* U x V = -z: faces the mirror. */
    add_grid(scene, t, v3(-4, -4, 5), v3(0, 8, 0), v3(8, 0, 0), UNIT2, 2, UNIT2, 2, 0, true);
    tmesh_commit(scene, t);
    return scene;
}

static void test_render_mirror(void)
{
    tmesh t;
    il_vec3 tint = v3(0.5f, 0.8f, 1.0f);
    il_scene *scene = mirror_scene(&t, tint);
    il_vec3 vrad[MAXV];
    for (uint32_t v = 0; v < t.m.num_vertices; v++)
        vrad[v] = t.m.vertex_surface[v] == 1 ? v3s(0.6f) : v3s(0.0f);
    il_render_stats stats = {0};
    stats.rays = 5;   /* added to, not overwritten */
    il_image img = render(scene, &t, vrad, W, H, (il_render_desc){.spp = 4}, &stats);
    il_vec3 c = pixel(&img, W / 2, H / 2);
    CHECK_NEAR(c.x, 0.6f * tint.x, 1e-6);
    CHECK_NEAR(c.y, 0.6f * tint.y, 1e-6);
    CHECK_NEAR(c.z, 0.6f * tint.z, 1e-6);
    /* A corner pixel misses the mirror: the background. */
    CHECK_NEAR(pixel(&img, 0, 0).z, 0.15f, 1e-7);
    /* Camera rays plus one bounce for those that met the mirror. */
    CHECK(stats.rays > 5 + (uint64_t)W * H * 4);
    CHECK(stats.rays < 5 + (uint64_t)W * H * 8);
    il_image_free(&img);

    /* max_depth 1 (one scattering event) still allows the mirror bounce. */
    img = render(scene, &t, vrad, W, H, (il_render_desc){.spp = 1, .max_depth = 1}, NULL);
    CHECK_NEAR(pixel(&img, W / 2, H / 2).y, 0.6f * tint.y, 1e-6);
    il_image_free(&img);
    tmesh_free(&t);
    il_scene_release(scene);
}

static void test_render_phong(void)
{
    il_error err = {0};
    il_vec3 env = v3(0.2f, 0.4f, 0.6f);
    /* Seen at 45 degrees, so the lobe's cosine factor is really tested. */
    il_scene *scene = new_scene(env, v3(0, -2.5f, 2.5f), v3s(0.0f));
    il_vec3 ks = v3(0.3f, 0.2f, 0.1f);
    const float n = 20.0f;
    uint32_t phong;
    CHECK_OK(il_scene_add_material(scene, &(il_material_desc){.type = IL_MATERIAL_PHONG, .diffuse = v3s(0.5f),
                                                               .specular = ks, .exponent = n},
                                   &phong, &err),
             &err);
    tmesh t;
    tmesh_init(&t);
    add_grid(scene, &t, v3(-1, -1, 0), v3(2, 0, 0), v3(0, 2, 0), UNIT2, 2, UNIT2, 2, phong, true);
    tmesh_commit(scene, &t);
    il_vec3 vrad[MAXV];
    for (uint32_t v = 0; v < t.m.num_vertices; v++)
        vrad[v] = v3s(0.25f);
    il_render_stats stats = {0};
    il_image img = render(scene, &t, vrad, W, H, (il_render_desc){.spp = 64, .seed = 11}, &stats);
    /* The glossy lobe sees the uniform sky.  Its throughput
     * ks (n+2)/(n+1) cos(theta_i) has mean ks (r.n) over the lobe around the
     * mirror direction r (the lobe's mean direction is (n+1)/(n+2) r), and
     * r.n = cos(theta_o) = -dir.z here; the part of the lobe below the
     * horizon (cos(alpha) < cos 45: probability 0.707^21 < 1e-3) is lost.
     * The ratio of the glossy part to that mean, over the 8x8 central
     * pixels (4096 samples), must be 1. */
    il_camera cam;
    il_camera_init(&cam, &scene->camera.desc, W, H);
    double ratio[3] = {0, 0, 0};
    for (uint32_t y = H / 2 - 4; y < H / 2 + 4; y++)
        for (uint32_t x = W / 2 - 4; x < W / 2 + 4; x++) {
            il_vec3 d = il_camera_ray_dir(&cam, (float)x + 0.5f, (float)y + 0.5f);
            float cos_o = -d.z;
            il_vec3 c = pixel(&img, x, y);
            ratio[0] += (c.x - 0.25f) / (ks.x * env.x * cos_o) / 64.0;
            ratio[1] += (c.y - 0.25f) / (ks.y * env.y * cos_o) / 64.0;
            ratio[2] += (c.z - 0.25f) / (ks.z * env.z * cos_o) / 64.0;
        }
    for (int k = 0; k < 3; k++)
        CHECK_NEAR(ratio[k], 0.9995, 0.006);
    /* Camera ray, glossy ray: two rays per sample where the quad is seen. */
    CHECK(stats.rays > (uint64_t)W * H * 64 + 64 * 64);
    CHECK(stats.rays < (uint64_t)W * H * 64 * 2);
    il_image_free(&img);
    tmesh_free(&t);
    il_scene_release(scene);
}

static void test_determinism(void)
{
    tmesh t;
    il_scene *scene = mirror_scene(&t, v3(0.9f, 0.7f, 0.5f));
    il_vec3 vrad[MAXV];
    for (uint32_t v = 0; v < t.m.num_vertices; v++) {
        il_vec3 p = t.m.positions[v];
        vrad[v] = v3(0.3f + 0.05f * p.x, 0.4f, 0.2f + 0.03f * p.y);
    }
    il_render_desc rd = {.spp = 9, .seed = 99, .threads = 1, .filter = IL_FILTER_GAUSSIAN,
                         .sampler = IL_SAMPLER_PCG};
    il_image a = render(scene, &t, vrad, 40, 24, rd, NULL);
    rd.threads = 2;
    il_image b = render(scene, &t, vrad, 40, 24, rd, NULL);
    CHECK(memcmp(a.rgb, b.rgb, sizeof(float) * 3 * 40 * 24) == 0);
    rd.seed = 100;
    il_image c = render(scene, &t, vrad, 40, 24, rd, NULL);
    CHECK(memcmp(a.rgb, c.rgb, sizeof(float) * 3 * 40 * 24) != 0);  /* the seed matters */
    il_image_free(&a);
    il_image_free(&b);
    il_image_free(&c);
    tmesh_free(&t);
    il_scene_release(scene);
}

/* Progress after every pass; returning false stops with complete passes. */
static bool stop_after_first(const il_render_progress *p, void *user)
{
    int *calls = user;
    (*calls)++;
    return p->passes_done < 1;
}

static void test_progress_and_errors(void)
{
    il_error err = {0};
    il_scene *scene = new_scene(v3s(0.3f), v3(0, 0, 3), v3s(0.0f));
    tmesh t;
    tmesh_init(&t);
    add_grid(scene, &t, v3(-1, -1, 0), v3(2, 0, 0), v3(0, 2, 0), UNIT1, 1, UNIT1, 1, 0, true);
    tmesh_commit(scene, &t);
    il_vec3 vrad[MAXV] = {{0}};
    /* 256x256 = 65536 pixels: one sample per pixel per pass. */
    il_film *film = NULL;
    CHECK_OK(il_film_create(256, 256, &film, &err), &err);
    int calls = 0;
    il_render_stats stats = {0};
    il_render_desc rd = {.spp = 5, .progress = stop_after_first, .progress_user = &calls};
    CHECK_OK(il_patch_render_film(scene, &t.m, vrad, film, &rd, &stats, &err), &err);
    CHECK(calls == 1);
    CHECK(stats.spp == 1);

    CHECK(il_patch_render_film(scene, &t.m, NULL, film, &rd, &stats, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "radiosity render") != NULL);
    il_scene *raw = NULL;
    CHECK_OK(il_scene_create(&raw, &err), &err);
    CHECK(il_patch_render_film(raw, &t.m, vrad, film, &rd, &stats, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "not committed") != NULL);
    il_scene_release(raw);
    il_film_release(film);
    tmesh_free(&t);
    il_scene_release(scene);
}

/* The same checks through the real mesher: a diffuse quad and a mirror,
 * meshed by il_patch_mesh_build with 2 subdivision levels. */
static void test_real_mesh(void)
{
    il_error err = {0};
    il_scene *scene = new_scene(v3(0.05f, 0.1f, 0.15f), v3(0, 0, 3), v3s(0.0f));
    il_vec3 tint = v3(0.5f, 0.8f, 1.0f);
    uint32_t mirror;
    CHECK_OK(il_scene_add_material(scene, &(il_material_desc){.type = IL_MATERIAL_MIRROR, .specular = tint},
                                   &mirror, &err),
             &err);
    /* The mirror at z = 0 facing +z; the wall at z = 5 facing -z. */
    const float pm[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const float pw[] = {-4, -4, 5, -4, 4, 5, 4, 4, 5, 4, -4, 5};
    const uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    CHECK_OK(il_scene_add_mesh(scene, &(il_mesh_desc){.num_vertices = 4, .num_triangles = 2, .positions = pm,
                                                       .indices = idx, .material = mirror},
                               &err),
             &err);
    CHECK_OK(il_scene_add_mesh(scene, &(il_mesh_desc){.num_vertices = 4, .num_triangles = 2, .positions = pw,
                                                       .indices = idx},
                               &err),
             &err);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    il_render_desc rd = {.spp = 4, .radiosity = &(il_radiosity_desc){.subdivisions = 2}};
    il_rad_settings settings;
    il_patch_mesh *mesh = NULL;
    CHECK_OK(il_rad_settings_resolve(scene, &rd, &settings, &err), &err);
    CHECK_OK(il_patch_mesh_build(scene, &(il_patch_sizing){settings.patch_size, settings.subdivisions}, &mesh, &err), &err);
    if (!mesh) {
        il_scene_release(scene);
        return;
    }
    CHECK(mesh->num_patches == 16);   /* the wall: one quad, 2 levels of 4 */
    il_vec3 *prad = calloc(mesh->num_patches, sizeof *prad);
    il_vec3 *vrad = calloc(mesh->num_vertices, sizeof *vrad);
    for (uint32_t i = 0; i < mesh->num_patches; i++)
        prad[i] = v3(0.6f, 0.6f, 0.6f);
    il_patch_vertex_radiance(mesh, prad, vrad);
    uint32_t used = 0;
    for (uint32_t v = 0; v < mesh->num_vertices; v++) {
        if (mesh->surfaces[mesh->vertex_surface[v]].diffuse) {
            used++;
            CHECK_NEAR(vrad[v].x, 0.6f, 1e-6);
        } else {
            CHECK(v3_is_zero(vrad[v]));
        }
    }
    CHECK(used == 25);    /* a 5x5 grid of vertices */

    il_film *film = NULL;
    il_image img = {0};
    CHECK_OK(il_film_create(W, H, &film, &err), &err);
    CHECK_OK(il_patch_render_film(scene, mesh, vrad, film, &rd, NULL, &err), &err);
    CHECK_OK(il_film_resolve(film, &img, &err), &err);
    il_vec3 c = pixel(&img, W / 2, H / 2);
    CHECK_NEAR(c.x, 0.6f * tint.x, 1e-6);
    CHECK_NEAR(c.y, 0.6f * tint.y, 1e-6);
    CHECK_NEAR(c.z, 0.6f * tint.z, 1e-6);
    CHECK_NEAR(pixel(&img, 0, 0).z, 0.15f, 1e-7);

    /* A step between the wall's halves (x < 0 and x > 0) marks patches. */
    il_rad_solution sol = {.num_patches = mesh->num_patches, .radiance = prad};
    for (uint32_t i = 0; i < mesh->num_patches; i++)
        prad[i] = v3s(mesh->patches[i].center.x < 0.0f ? 1.0f : 3.0f);
    bool *split = calloc(mesh->num_patches, sizeof *split);
    uint32_t marked = il_rad_mark_split(mesh, &sol, 0.5f, split);
    CHECK(marked == 8);   /* the two columns beside x = 0 */
    for (uint32_t i = 0; i < mesh->num_patches; i++) {
        /* Only patches touching x = 0 (within one patch width, 2 m). */
        float dx = fabsf(mesh->patches[i].center.x);
        if (split[i])
            CHECK(dx < 2.0f);
        else
            CHECK(dx > 0.5f);
    }
    free(split);
    il_image_free(&img);
    il_film_release(film);
    free(prad);
    free(vrad);
    il_patch_mesh_release(mesh);
    il_scene_release(scene);
}

/* ---------------------------------------------------------------- adaptive */

static void test_mark_split(void)
{
    il_scene *scene = new_scene(v3s(1.0f), v3(0, 0, 3), v3s(0.0f));
    tmesh t;
    tmesh_init(&t);
    /* A 4x4 grid (patch g + j*4 + i) with a step between columns 1 and 2;
     * a second surface of one very bright patch right beside column 3 but
     * sharing no vertex; a third surface, 4x1, nearly black. */
    static const float q4[] = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f};
    uint32_t g = add_grid(scene, &t, v3(-1, -1, 0), v3(2, 0, 0), v3(0, 2, 0), q4, 4, q4, 4, 0, true);
    uint32_t s2 = add_grid(scene, &t, v3(1, -1, 0), v3(0.5f, 0, 0), v3(0, 2, 0), UNIT1, 1, UNIT1, 1, 0, true);
    uint32_t s3 = add_grid(scene, &t, v3(-1, -1, 1), v3(2, 0, 0), v3(0, 2, 0), q4, 4, UNIT1, 1, 0, true);
    uint32_t np = t.m.num_patches;
    CHECK(np == 16 + 1 + 4);

    il_vec3 rad[MAXP];
    il_rad_solution sol = {.num_patches = np, .radiance = rad};
    /* Columns 1.0, 1.2 | 10, 11: within a column pair the change is below
     * half the larger value, across the step it is not. */
    static const float col[4] = {1.0f, 1.2f, 10.0f, 11.0f};
    for (uint32_t j = 0; j < 4; j++)
        for (uint32_t i = 0; i < 4; i++)
            rad[g + 4 * j + i] = v3s(col[i]);
    rad[s2] = v3s(100.0f);   /* brightest: the dark floor is 1e-4 */
    /* 0 vs 2e-5 is below the floor; 0 vs 1e-3 is a real step. */
    static const float dark[4] = {0.0f, 2e-5f, 0.0f, 1e-3f};
    for (uint32_t i = 0; i < 4; i++)
        rad[s3 + i] = v3s(dark[i]);

    bool split[MAXP];
    for (uint32_t i = 0; i < np; i++)
        split[i] = true;   /* every entry is written */
    uint32_t marked = il_rad_mark_split(&t.m, &sol, 0.5f, split);
    CHECK(marked == 8 + 2);
    uint32_t count = 0;
    for (uint32_t j = 0; j < 4; j++)
        for (uint32_t i = 0; i < 4; i++)
            CHECK(split[g + 4 * j + i] == (i == 1 || i == 2));
    CHECK(!split[s2]);
    CHECK(!split[s3] && !split[s3 + 1] && split[s3 + 2] && split[s3 + 3]);
    for (uint32_t i = 0; i < np; i++)
        count += split[i];
    CHECK(count == marked);

    /* Colour enters through luminance: a red/green step of equal luminance
     * is no step (their largest components differ threefold). */
    for (uint32_t j = 0; j < 4; j++)
        for (uint32_t i = 0; i < 4; i++)
            rad[g + 4 * j + i] = i < 2 ? v3(1.0f / 0.2126f, 0, 0) : v3(0, 1.0f / 0.7152f, 0);
    marked = il_rad_mark_split(&t.m, &sol, 0.5f, split);
    CHECK(marked == 2);   /* only the dark surface's step */
    /* A huge threshold marks nothing. */
    CHECK(il_rad_mark_split(&t.m, &sol, 1e6f, split) == 0);
    tmesh_free(&t);
    il_scene_release(scene);
}

int main(void)
{
    test_vertex_average();
    test_render_constant_and_background();
    test_render_back_side();
    test_render_gradient();
    test_render_mirror();
    test_render_phong();
    test_determinism();
    test_progress_and_errors();
    test_mark_split();
    test_real_mesh();
    return check_report();
}
