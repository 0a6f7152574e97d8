/* The GPU path-tracing megakernel (src/cuda/pt_kernel.cu) on the Cornell
 * box and on the Cornell box with the Stanford dragon against (a) the same
 * kernel compiled by gcc with the same random streams: the same image and
 * ray count up to float rounding (the GPU's sinf/cosf can send a few paths
 * another way), and (b) the CPU path tracer il_render: the same mean
 * radiance within noise; the same for the Cornell box with a textured
 * panel, lit by an environment map, and lit by the sun and a sky with a
 * mirror that shows the sun's disc.  Then the progressive render's stops (il_cuda_run):
 * by its progress callback and by its time limit; and its sums over a
 * million samples per pixel.  Exits 77 (a skip for
 * ctest) without a GPU or driver, as on CI. */
#include <stdlib.h>
#include <string.h>
#include "cuda_test.h"
#include "kernel/kernel_scene.h"
#include "scene/scene.h"

#define W 64
#define H 64
#define SPP 256

/* The GPU image of the scene against the kernel on the CPU and il_render. */
static void compare(il_scene *s)
{
    il_error err = {0};
    float *gpu = calloc(3 * W * H, sizeof *gpu), *cpu = calloc(3 * W * H, sizeof *cpu);
    il_cuda_run run = {0};
    CHECK_OK(il_cuda_render_pt(s, W, H, SPP, 8, 3, gpu, &run, &err), &err);

    il_kscene ks;
    CHECK_OK(il_kscene_build_pt(s, W, H, 8, 3, &ks, &err), &err);
    uint64_t cpu_rays = 0;
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double acc[3] = {0, 0, 0};
            for (uint32_t i = 0; i < SPP; i++) {
                uint32_t r = 0;
                ilk_vec3 L = ilk_path_sample(&ks.view, x, y, i, &r);
                cpu_rays += r;
                acc[0] += L.x; acc[1] += L.y; acc[2] += L.z;
            }
            for (int c = 0; c < 3; c++)
                cpu[3 * (y * W + x) + c] = (float)(acc[c] / SPP);
        }
    il_kscene_free(&ks);
    /* The same paths cast the same rays, up to the few that the GPU's
     * sinf/cosf send another way. */
    printf("rays: gpu %llu, kernel on cpu %llu; %u spp done\n", (unsigned long long)run.rays,
           (unsigned long long)cpu_rays, run.spp_done);
    CHECK(run.spp_done == SPP);
    CHECK_REL((double)run.rays, (double)cpu_rays, 1e-3);

    cuda_test_compare(s, W, H, gpu, cpu, SPP, 0.03);
    free(gpu);
    free(cpu);
}

/* The Cornell box with a checker-textured Phong panel on its floor (its
 * kd + ks above 1 where the checker is bright: scaled per hit), or lit
 * through its open front by a latitude-longitude environment map turned by
 * 40 degrees (a bright patch in a gradient), or by a sun 5 degrees up
 * behind the camera, 8 degrees across, and a uniform sky, with a mirror
 * over the back wall in which the camera sees the sun's disc (ilk_discs,
 * and its light drawn across the disc in ilk_direct). */
static il_scene *cornell_with(bool panel, bool env_map, bool sun)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_load("cornell", NULL, &s, &err), &err);
    if (!s)
        return NULL;
    if (panel) {
        float tx[8 * 8 * 3];
        for (int i = 0; i < 64; i++)
            for (int c = 0; c < 3; c++)
                tx[3 * i + c] = ((i % 8) / 2 + (i / 8) / 2) % 2 ? 0.9f - 0.2f * c : 0.1f + 0.15f * c;
        uint32_t tex = 0, mat = 0;
        CHECK_OK(il_scene_add_texture(s, 8, 8, tx, &tex, &err), &err);
        CHECK_OK(il_scene_add_material(s, &(il_material_desc){.name = "checker", .type = IL_MATERIAL_PHONG,
                                       .diffuse = {1.0f, 0.9f, 0.8f}, .specular = {0.3f, 0.3f, 0.3f},
                                       .exponent = 20.0f, .diffuse_texture = tex}, &mat, &err), &err);
        float p[] = {0.1f, 0.01f, 0.1f, 0.45f, 0.01f, 0.1f, 0.45f, 0.01f, 0.45f, 0.1f, 0.01f, 0.45f};
        float uv[] = {0, 0, 2, 0, 2, 2, 0, 2};
        uint32_t ix[] = {0, 2, 1, 0, 3, 2}; /* facing up */
        CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.num_vertices = 4, .num_triangles = 2, .positions = p,
                                                       .uvs = uv, .indices = ix, .material = mat}, &err), &err);
    }
    if (env_map) {
        float px[32 * 16 * 3];
        for (uint32_t y = 0; y < 16; y++)
            for (uint32_t x = 0; x < 32; x++) {
                float t = y / 16.0f, *q = px + 3 * (y * 32 + x);
                bool patch = y >= 5 && y < 8 && x >= 14 && x < 18;
                q[0] = patch ? 12.0f : 0.2f + 0.4f * t;
                q[1] = patch ? 11.0f : 0.3f + 0.1f * t;
                q[2] = patch ? 9.0f : 0.6f - 0.4f * t;
            }
        il_image map = {.width = 32, .height = 16, .rgb = px};
        CHECK_OK(il_scene_set_environment(s, &(il_environment_desc){.map = &map, .rotation = 40.0f}, &err), &err);
    }
    if (sun) {
        uint32_t mirror = 0;
        CHECK_OK(il_scene_add_material(s, &(il_material_desc){.name = "mirror", .type = IL_MATERIAL_MIRROR,
                                       .specular = {0.9f, 0.85f, 0.8f}}, &mirror, &err), &err);
        /* 1 mm in front of the back wall (z = 0.559 m), facing the camera. */
        float p[] = {0.05f, 0.05f, 0.558f, 0.5f, 0.05f, 0.558f, 0.5f, 0.5f, 0.558f, 0.05f, 0.5f, 0.558f};
        uint32_t ix[] = {0, 2, 1, 0, 3, 2};
        CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.num_vertices = 4, .num_triangles = 2, .positions = p,
                                                       .indices = ix, .material = mirror}, &err), &err);
        il_light_desc l = {.type = IL_LIGHT_DIRECTIONAL, .direction = {0.1f, -0.0875f, 1.0f},
                           .intensity = {3.0f, 2.8f, 2.5f}, .diameter = 8.0f};
        CHECK_OK(il_scene_add_light(s, &l, &err), &err);
        CHECK_OK(il_scene_set_environment(s, &(il_environment_desc){.radiance = {0.2f, 0.3f, 0.5f}}, &err), &err);
    }
    if (il_scene_commit(s, &err) != IL_OK) {
        CHECK_OK(IL_ERR_INVALID, &err);
        il_scene_release(s);
        return NULL;
    }
    return s;
}

/* Stops the render at its second report. */
static bool stop_at_two(const il_render_progress *p, void *user)
{
    uint32_t *reports = user;
    CHECK(p->film == NULL && p->passes_done == 16 * (*reports + 1) && p->rays > 0);
    return ++*reports < 2;
}

/* A render stopped by its progress callback after two launches, and one
 * stopped by its time limit after the first: each the very image of a
 * render asked for that many samples. */
static void stops(il_scene *s)
{
    il_error err = {0};
    size_t bytes = sizeof(float) * 3 * W * H;
    float *rgb = malloc(bytes), *ref = malloc(bytes);
    uint32_t reports = 0;
    il_cuda_run run = {.progress = stop_at_two, .progress_user = &reports};
    CHECK_OK(il_cuda_render_pt(s, W, H, SPP, 8, 3, rgb, &run, &err), &err);
    CHECK(reports == 2 && run.spp_done == 32 && run.rays > 0);
    CHECK_OK(il_cuda_render_pt(s, W, H, 32, 8, 3, ref, NULL, &err), &err);
    CHECK(memcmp(rgb, ref, bytes) == 0);
    il_cuda_run timed = {.time_limit = 1e-9};
    CHECK_OK(il_cuda_render_pt(s, W, H, 0, 8, 3, rgb, &timed, &err), &err);
    CHECK(timed.spp_done == 16);
    CHECK_OK(il_cuda_render_pt(s, W, H, 16, 8, 3, ref, NULL, &err), &err);
    CHECK(memcmp(rgb, ref, bytes) == 0);
    printf("stopped by the callback after %u spp, by a 1 ns limit after %u spp\n", run.spp_done, timed.spp_done);
    free(rgb);
    free(ref);
}

/* The sums of a long render.  A camera facing a black emitter of radiance
 * 0.1 sees exactly 0.1f in every sample, so each launch adds the same batch
 * sum a (16 samples) to every pixel.  After 2^20 samples (65,536 launches)
 * the mean must be the 16-sample image's, bit for bit: the double sum of
 * 65,536 copies of a is exact.  A float sum is not: past 2^16 it rounds
 * each a of about 1.6 to whole ulps (the same sums in float on the CPU end
 * 6e-4 off), and the build that summed in float failed this check. */
static void long_accumulation(void)
{
    il_error err = {0};
    il_scene *s = new_scene();
    il_material_desc d = {.type = IL_MATERIAL_DIFFUSE, .diffuse = v3s(0.0f), .emission = v3s(0.1f)};
    uint32_t m = add_material(s, d);
    add_quad(s, v3(0, 0, -1), v3(10, 0, 0), v3(0, 10, 0), m);
    set_camera(s, v3(0, 0, 0), v3(0, 0, -1), v3(0, 1, 0), 40.0f);
    commit(s);
    enum { side = 8, values = 3 * side * side };
    float ref[values], rgb[values];
    CHECK_OK(il_cuda_render_pt(s, side, side, 16, 8, 3, ref, NULL, &err), &err);
    il_cuda_run run = {0};
    CHECK_OK(il_cuda_render_pt(s, side, side, 1u << 20, 8, 3, rgb, &run, &err), &err);
    int differ = 0;
    for (int i = 0; i < values; i++)
        differ += rgb[i] != ref[i];
    printf("2^20 spp of a constant 0.1: %u spp done, pixel 0 %.9g (16 spp: %.9g), %d of %d values differ\n",
           run.spp_done, (double)rgb[0], (double)ref[0], differ, (int)values);
    CHECK(run.spp_done == 1u << 20);
    CHECK(differ == 0);
    CHECK_REL((double)ref[0], 0.1, 1e-6);
    il_scene_release(s);
}

int main(void)
{
    if (cuda_test_require_gpu() != 0)
        return 77;
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();
    compare(s);
    stops(s);
    il_scene_release(s);
    long_accumulation();

    /* The Cornell box with the Stanford dragon (47,806 triangles). */
    s = load_committed(IL_SOURCE_DIR "/bench/scenes/cornell-dragon.json");
    if (s) {
        compare(s);
        il_scene_release(s);
    }
    /* A diffuse texture (ilk_material_at), an environment map
     * (ilk_environment), the sun's disc and a sky. */
    for (int v = 0; v < 3; v++) {
        s = cornell_with(v == 0, v == 1, v == 2);
        if (s) {
            compare(s);
            il_scene_release(s);
        }
    }
    return check_report();
}
