/* The whole radiosity method: il_rad_run (stats, the adaptive pass), il_bake
 * (meshes grouped back by scene mesh, per-vertex radiance and normals,
 * mirror triangles kept with zero radiance) and il_render with
 * IL_METHOD_RADIOSITY. */
#include "rad_scenes.h"

#define NUM_SCENE_MESHES 8u

/* The coloured room plus a small mirror standing on the floor. */
static il_scene *room_with_mirror(void)
{
    il_scene *s = coloured_room();
    il_material_desc mirror = {.type = IL_MATERIAL_MIRROR};
    uint32_t m = add_material(s, mirror);
    /* A vertical square at z = 0.8 facing -z, x in [0.4, 0.6], y in [0, 0.2]. */
    add_quad(s, v3(0.5f, 0.1f, 0.8f), v3(0, 0.1f, 0), v3(0.1f, 0, 0), m);
    /* Inside the room (the default camera would look at the walls' backs). */
    set_camera(s, v3(0.5f, 0.5f, 0.97f), v3(0.5f, 0.4f, 0.0f), v3(0, 1, 0), 70.0f);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    return s;
}

static il_radiosity_desc run_options(void)
{
    il_radiosity_desc rad = {.subdivisions = 2, .form_factors = IL_FF_RAYCAST, .ray_samples = 512};
    return rad;
}

static void test_run_stats(const il_scene *s)
{
    il_radiosity_desc rad = run_options();
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .threads = 2, .radiosity = &rad};
    il_patch_mesh *mesh = NULL;
    il_rad_solution sol;
    il_vec3 *vr = NULL;
    il_render_stats st;
    CHECK_OK(il_rad_run(s, &rd, &mesh, &sol, &vr, &st, &g_err), &g_err);
    if (!mesh)
        return;
    const il_radiosity_stats *r = &st.radiosity;
    CHECK(r->num_patches == mesh->num_patches && r->num_patches == sol.num_patches);
    CHECK(r->num_surfaces == mesh->num_surfaces);
    CHECK(r->steps == sol.steps && r->steps > 0);
    CHECK(r->unshot_fraction < 0.01 && r->unshot_fraction == sol.unshot_fraction);
    CHECK(r->rows_computed > 0 && r->rows_computed <= mesh->num_patches);
    CHECK(r->cache_bytes > 0);
    CHECK(r->peak_bytes > r->cache_bytes);
    CHECK(r->seconds_mesh >= 0.0 && r->seconds_form_factors >= 0.0);
    CHECK(r->seconds_solve >= 0.0);
    for (uint32_t v = 0; v < mesh->num_vertices; v++)
        CHECK(v3_is_finite(vr[v]) && vr[v].x >= 0.0f);
    uint32_t coarse = mesh->num_patches;
    il_rad_solution_free(&sol);
    il_patch_mesh_release(mesh);
    free(vr);

    /* Adaptive subdivision: more patches (the lamp's shadow and the corners
     * vary), still converged. */
    rad.adaptive_threshold = 0.2f;
    CHECK_OK(il_rad_run(s, &rd, NULL, NULL, NULL, &st, &g_err), &g_err);
    printf("adaptive: %u -> %u patches, %u steps in all\n", coarse, st.radiosity.num_patches,
           st.radiosity.steps);
    CHECK(st.radiosity.num_patches > coarse);
    CHECK(st.radiosity.unshot_fraction < 0.01);
}

static void test_bake(const il_scene *s)
{
    il_radiosity_desc rad = run_options();
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .threads = 2, .radiosity = &rad};
    /* The reference: the same run (deterministic) through the internal API. */
    il_patch_mesh *mesh = NULL;
    il_vec3 *vr = NULL;
    CHECK_OK(il_rad_run(s, &rd, &mesh, NULL, &vr, NULL, &g_err), &g_err);
    il_bake_result *bake = NULL;
    CHECK_OK(il_bake(s, &rd, &bake, &g_err), &g_err);
    if (!mesh || !bake) {
        if (mesh)
            il_patch_mesh_release(mesh);
        free(vr);
        il_bake_release(bake);
        return;
    }
    CHECK(bake->num_meshes == NUM_SCENE_MESHES);
    CHECK(bake->stats.radiosity.num_patches == mesh->num_patches);
    uint64_t tris = 0;
    for (uint32_t m = 0; m < bake->num_meshes; m++) {
        const il_bake_mesh *b = &bake->meshes[m];
        tris += b->num_triangles;
        CHECK(b->num_triangles > 0 && b->num_vertices > 0);
        CHECK(b->material == s->meshes[m].material);
        for (uint32_t k = 0; k < 3 * b->num_triangles; k++)
            CHECK(b->indices[k] < b->num_vertices);
        bool mirror = m == NUM_SCENE_MESHES - 1, lamp = m == 6;
        for (uint32_t v = 0; v < b->num_vertices; v++) {
            const float *n = b->normals + 3 * (size_t)v, *L = b->radiance + 3 * (size_t)v;
            il_vec3 p = v3(b->positions[3 * v], b->positions[3 * v + 1], b->positions[3 * v + 2]);
            CHECK_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-5);
            if (m == 0) /* the floor faces up */
                CHECK_NEAR(n[1], 1.0, 1e-6);
            if (mirror) {
                CHECK_NEAR(n[2], -1.0, 1e-6);
                CHECK(L[0] == 0.0f && L[1] == 0.0f && L[2] == 0.0f);
                continue;
            }
            if (lamp)
                CHECK(L[0] >= 7.999f);
            else
                CHECK(L[0] > 0.0f && L[1] > 0.0f);
            /* The same radiance as the rad vertex at this position in a
             * surface of this scene mesh. */
            bool found = false;
            for (uint32_t g = 0; g < mesh->num_vertices && !found; g++) {
                il_vec3 q = mesh->positions[g];
                if (q.x == p.x && q.y == p.y && q.z == p.z &&
                    mesh->surfaces[mesh->vertex_surface[g]].mesh == m) {
                    found = true;
                    CHECK(L[0] == vr[g].x && L[1] == vr[g].y && L[2] == vr[g].z);
                }
            }
            CHECK(found);
        }
    }
    CHECK(tris == mesh->num_tris);
    il_bake_release(bake);
    il_patch_mesh_release(mesh);
    free(vr);
}

static void test_render(const il_scene *s)
{
    il_radiosity_desc rad = run_options();
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .threads = 2, .spp = 2, .radiosity = &rad};
    il_film *film = NULL;
    CHECK_OK(il_film_create(24, 16, &film, &g_err), &g_err);
    il_render_stats st;
    CHECK_OK(il_render(s, film, &rd, &st, &g_err), &g_err);
    CHECK(st.spp == 2);
    CHECK(st.rays > 0);
    CHECK(st.radiosity.num_patches > 100);
    CHECK(st.radiosity.seconds_render >= 0.0);
    il_image img = {0};
    CHECK_OK(il_film_resolve(film, &img, &g_err), &g_err);
    double sum = 0.0;
    bool finite = true;
    for (size_t k = 0; img.rgb && k < 3u * img.width * img.height; k++) {
        finite = finite && isfinite(img.rgb[k]);
        sum += img.rgb[k];
    }
    CHECK(finite);
    CHECK(sum > 0.0);
    il_image_free(&img);
    il_film_release(film);
}

int main(void)
{
    il_scene *s = room_with_mirror();
    test_run_stats(s);
    test_bake(s);
    test_render(s);
    il_scene_release(s);
    return check_report();
}
