/* Hierarchical radiosity in a closed box whose six walls all emit E and
 * reflect rho: the exact radiance is E/(1-rho) everywhere (B = E + rho B).
 * Each wall's area-weighted mean must be within 1%.  Single leaves are
 * looser: a leaf in a corner inherits links its ancestors made from their
 * centres (each within bf_eps, but a hundred of them err the same way), a
 * known trait of BF refinement (Hanrahan et al. 1991, section 6); the
 * spread is printed and bounded at 20%.  Also checks that the roots are the
 * input polygons, quads kept whole.  Then a bright box (rho 0.95) at the
 * default energy_eps: each wall within 1% of E/(1-rho) = 20 E, where
 * SPLASH-2's test (the last change below energy_eps) stopped 8.1% low, after
 * 48 iterations; and a box of albedo 1 stops as stalled. */
#include "hr_scenes.h"
#include "methods/radiosity/rad_stall.h"

static void leaf_range(const il_hr_elem *e, void *user)
{
    double *r = user;
    double b = e->radiance.y;
    r[0] = b < r[0] ? b : r[0];
    r[1] = b > r[1] ? b : r[1];
    r[2] += 1.0;
    r[3 + 2 * e->root] += (double)e->area * b;
    r[4 + 2 * e->root] += e->area;
}

/* The 3 m box of albedo rho, every wall emitting E, solved with coarse
 * links (the light is even: little to refine) at the default energy_eps. */
static il_scene *coarse_box_run(float rho, float E, hr_case *c)
{
    il_scene *s = new_scene();
    uint32_t m = diffuse_material(s, v3s(rho), v3s(E));
    const uint32_t mat[6] = {m, m, m, m, m, m};
    add_box_room(s, 3.0f, mat);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    il_hr_desc hd = {.bf_eps = 0.05f, .area_eps = 0.01f, .vis_rays = 4};
    il_render_desc rd = {.method = IL_METHOD_HR, .threads = 2, .hr = &hd};
    CHECK_OK(hr_case_run(s, &rd, c), &g_err);
    printf("box of albedo %.2f: %u iterations, %u sweeps, converged %d, stalled %d\n", (double)rho,
           c->solver.stats.iterations, c->solver.stats.sweeps, (int)c->solver.stats.converged,
           (int)c->solver.stats.stalled);
    return s;
}

/* A box of albedo 0.95: the light bounces about 20 times, and the solve
 * must not stop while much of it is still to come (hr_solve.c,
 * energy_left). */
static void bright_box(void)
{
    const float rho = 0.95f, E = 1.0f;
    hr_case c;
    il_scene *s = coarse_box_run(rho, E, &c);
    hr_print_stats("bright furnace", &c.solver.stats);
    CHECK(c.solver.stats.converged);
    double r[3 + 12] = {1e30, -1e30, 0};
    for (uint32_t i = 0; i < c.solver.num_roots; i++)
        hr_visit_leaves(&c.solver.roots[i], leaf_range, r);
    double expect = E / (1.0 - rho);
    for (int w = 0; w < 6; w++) {
        printf("bright wall %d: mean %.5f (%+.2f%%)\n", w, r[3 + 2 * w] / r[4 + 2 * w],
               100.0 * (r[3 + 2 * w] / r[4 + 2 * w] / expect - 1.0));
        CHECK_REL(r[3 + 2 * w] / r[4 + 2 * w], expect, 0.01);
    }
    hr_case_free(&c);
    il_scene_release(s);
}

/* Albedo 1: no light leaves, every sweep adds as much as the last; the
 * solve must stop by itself as stalled (radiosity's test, rad_stall.h),
 * not run its 100 iterations of up to 64 sweeps. */
static void white_box(void)
{
    hr_case c;
    il_scene *s = coarse_box_run(1.0f, 1.0f, &c);
    const il_hr_stats *st = &c.solver.stats;
    CHECK(st->stalled && !st->converged && !st->stopped);
    CHECK(st->sweeps <= 3 * IL_RAD_STALL_WINDOW * st->iterations);
    hr_case_free(&c);
    il_scene_release(s);
}

int main(void)
{
    const float rho = 0.6f, E = 2.5f;
    il_scene *s = new_scene();
    uint32_t m = diffuse_material(s, v3s(rho), v3s(E));
    const uint32_t mat[6] = {m, m, m, m, m, m};
    add_box_room(s, 3.0f, mat);
    set_camera(s, v3(1.5f, 1.5f, 2.9f), v3(1.5f, 1.5f, 0.0f), v3(0, 1, 0), 60.0f);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);

    il_hr_desc hd = {.energy_eps = 1e-5f};
    il_render_desc rd = {.method = IL_METHOD_HR, .threads = 2, .hr = &hd};
    hr_case c;
    CHECK_OK(hr_case_run(s, &rd, &c), &g_err);
    if (c.mesh) {
        CHECK(c.mesh->num_patches == 6);
        for (uint32_t i = 0; i < c.mesh->num_patches; i++)
            CHECK(c.mesh->patches[i].num_corners == 4);
    }
    hr_print_stats("furnace", &c.solver.stats);
    double r[3 + 12] = {1e30, -1e30, 0};
    for (uint32_t i = 0; i < c.solver.num_roots; i++)
        hr_visit_leaves(&c.solver.roots[i], leaf_range, r);
    double expect = E / (1.0 - rho);
    printf("leaves %.0f: radiance %.5f .. %.5f (expect %.5f)\n", r[2], r[0], r[1], expect);
    for (int w = 0; w < 6; w++) {
        printf("wall %d: mean %.5f (%+.2f%%)\n", w, r[3 + 2 * w] / r[4 + 2 * w],
               100.0 * (r[3 + 2 * w] / r[4 + 2 * w] / expect - 1.0));
        CHECK_REL(r[3 + 2 * w] / r[4 + 2 * w], expect, 0.01);
        CHECK_NEAR(r[4 + 2 * w], 9.0, 1e-3); /* the leaves tile the wall */
    }
    CHECK_REL(r[0], expect, 0.2);
    CHECK_REL(r[1], expect, 0.2);
    CHECK(c.solver.stats.elements > 6); /* light varies near the corners: refined */
    hr_case_free(&c);

    /* Through il_render, from inside the box: the image's mean is E/(1-rho)
     * (within 2%: the pixels weight the walls unevenly). */
    il_film *film = NULL;
    CHECK_OK(il_film_create(32, 32, &film, &g_err), &g_err);
    il_render_stats st;
    rd.spp = 1;
    CHECK_OK(il_render(s, film, &rd, &st, &g_err), &g_err);
    il_image img = {0};
    CHECK_OK(il_film_resolve(film, &img, &g_err), &g_err);
    CHECK_REL(image_mean(&img, 1), expect, 0.02);
    CHECK(st.hr.patches == 6 && st.hr.iterations > 1 && st.hr.links > 0);
    il_image_free(&img);
    il_film_release(film);
    il_scene_release(s);
    bright_box();
    white_box();
    return check_report();
}
