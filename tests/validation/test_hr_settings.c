/* Hierarchical radiosity settings: defaults resolve, bad values give a
 * clear IL_ERR_INVALID through il_render and il_bake, and HR bakes. */
#include <math.h>
#include <stdlib.h>
#include "hr_scenes.h"

static void expect_bad(const il_scene *s, il_hr_desc hd, const char *needle)
{
    il_film *film = NULL;
    CHECK_OK(il_film_create(8, 8, &film, &g_err), &g_err);
    il_render_desc rd = {.method = IL_METHOD_HR, .threads = 1, .hr = &hd};
    il_error e = {0};
    CHECK(il_render(s, film, &rd, NULL, &e) == IL_ERR_INVALID);
    CHECK(strstr(e.message, needle) != NULL);
    il_bake_result *b = NULL;
    il_error e2 = {0};
    CHECK(il_bake(s, &rd, &b, &e2) == IL_ERR_INVALID && b == NULL);
    CHECK(strstr(e2.message, needle) != NULL);
    il_film_release(film);
}

int main(void)
{
    il_render_desc rd = {.method = IL_METHOD_HR};
    il_hr_settings set;
    CHECK_OK(il_hr_settings_resolve(&rd, &set, &g_err), &g_err);
    CHECK_NEAR(set.bf_eps, 0.015, 1e-7);
    CHECK_NEAR(set.area_eps, 2000.0 / (1700.0 * 1700.0), 1e-9);
    CHECK_NEAR(set.energy_eps, 0.005, 1e-7);
    CHECK(set.vis_rays == 16 && set.max_iterations == 100 && set.threads >= 1);
    CHECK(set.link_memory_limit > 0);

    il_scene *s = hr_room(false, true);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    expect_bad(s, (il_hr_desc){.bf_eps = -0.1f}, "bf-eps");
    expect_bad(s, (il_hr_desc){.bf_eps = NAN}, "bf-eps");
    expect_bad(s, (il_hr_desc){.area_eps = INFINITY}, "area-eps");
    expect_bad(s, (il_hr_desc){.energy_eps = 2.0f}, "energy-eps");
    expect_bad(s, (il_hr_desc){.vis_rays = 5000}, "vis-rays");
    expect_bad(s, (il_hr_desc){.max_iterations = 0xffffffffu}, "max-iterations");

    /* An unknown method is refused (a value past every method: methods
     * after HR, such as photon mapping, are valid). */
    il_film *film = NULL;
    CHECK_OK(il_film_create(8, 8, &film, &g_err), &g_err);
    il_render_desc bad = {.method = (il_method)1000};
    il_error e = {0};
    CHECK(il_render(s, film, &bad, NULL, &e) == IL_ERR_INVALID);
    CHECK(strstr(e.message, "unknown method") != NULL);
    il_film_release(film);

    /* The initial links are held to a limit (half the physical memory;
     * here 100 bytes): a scene whose links exceed it is refused with a
     * message saying why, and one that fits solves. */
    il_patch_mesh *roots = NULL;
    CHECK_OK(il_hr_root_mesh(s, &roots, &g_err), &g_err);
    il_hr_settings tight = set;
    tight.link_memory_limit = 100;
    il_hr_solver solver;
    il_error me = {0};
    CHECK(il_hr_solve(s, roots, &tight, &solver, &me) == IL_ERR_MEMORY);
    CHECK(strstr(me.message, "13 patches make") && strstr(me.message, "initial links") &&
          strstr(me.message, "--method radiosity"));
    tight.link_memory_limit = 13 * 12 * sizeof(il_hr_link); /* every ordered pair */
    tight.max_iterations = 1;
    CHECK_OK(il_hr_solve(s, roots, &tight, &solver, &g_err), &g_err);
    CHECK(solver.stats.links > 0);
    il_hr_solver_free(&solver);
    il_patch_mesh_release(roots);

    /* A mesh of more than a thousand patches is judged by a sample of its
     * rows first: far past the limit, it is refused on the estimate. */
    il_scene *big = hr_room(false, true);
    add_ball(big, v3(0.5f, 0.6f, 0.5f), 0.15f, 0);
    CHECK_OK(il_scene_commit(big, &g_err), &g_err);
    CHECK_OK(il_hr_root_mesh(big, &roots, &g_err), &g_err);
    CHECK(roots->num_patches > 1024);
    tight.link_memory_limit = 50 * sizeof(il_hr_link);
    il_error be = {0};
    CHECK(il_hr_solve(big, roots, &tight, &solver, &be) == IL_ERR_MEMORY);
    CHECK(strstr(be.message, "patches make about") && strstr(be.message, "--method radiosity"));
    /* Within eight times the limit the estimate is not trusted: the pairs
     * are counted up to the limit, then refused.  (The 13-patch room above,
     * with no estimate, was refused by the running count of the links.) */
    const char *about = strstr(be.message, "about ");
    unsigned long long estimate = about ? strtoull(about + 6, NULL, 10) : 0;
    CHECK(estimate > 100);
    tight.link_memory_limit = (size_t)(estimate / 4) * sizeof(il_hr_link);
    il_error ce = {0};
    CHECK(il_hr_solve(big, roots, &tight, &solver, &ce) == IL_ERR_MEMORY);
    CHECK(strstr(ce.message, "patches make more than") && strstr(ce.message, "--method radiosity"));
    il_patch_mesh_release(roots);
    il_scene_release(big);

    /* HR bakes: every scene mesh, positive radiance on the lit walls, the
     * lamp's vertices at least its emission. */
    il_hr_desc one = {.vis_rays = 1, .max_iterations = 3};
    il_render_desc bd = {.method = IL_METHOD_HR, .threads = 2, .hr = &one};
    il_bake_result *b = NULL;
    CHECK_OK(il_bake(s, &bd, &b, &g_err), &g_err);
    if (b) {
        CHECK(b->num_meshes == s->num_meshes);
        CHECK(b->stats.hr.iterations <= 3 && b->stats.hr.patches == 13);
        CHECK(b->meshes[0].num_vertices >= 4 && b->meshes[0].radiance[1] > 0.0f);
        CHECK(b->meshes[6].radiance[1] >= 7.5f * 0.99f);
    }
    il_bake_release(b);
    il_scene_release(s);
    return check_report();
}
