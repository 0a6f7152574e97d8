/* Hierarchical radiosity gives the same elements, links and radiances
 * whatever the thread count and run: the statistics' counts are equal and
 * the leaves' radiances (in quadtree order) and the baked per-vertex
 * radiances are bit-identical with 1 and 2 threads, twice.  The scene has
 * a point light too, so the direct light of the elements is covered. */
#include "hr_scenes.h"

typedef struct leaves { float *rgb; size_t n, cap; } leaves;

static void collect(const il_hr_elem *e, void *user)
{
    leaves *l = user;
    if (l->n + 3 > l->cap) {
        l->cap = 2 * l->cap + 48;
        l->rgb = realloc(l->rgb, l->cap * sizeof *l->rgb);
    }
    l->rgb[l->n++] = e->radiance.x;
    l->rgb[l->n++] = e->radiance.y;
    l->rgb[l->n++] = e->radiance.z;
}

static il_hr_stats solve(const il_scene *s, int threads, leaves *out)
{
    /* The defaults: thousands of links are split on both sides. */
    il_hr_desc hd = {0};
    il_render_desc rd = {.method = IL_METHOD_HR, .threads = threads, .seed = 11, .hr = &hd};
    hr_case c;
    CHECK_OK(hr_case_run(s, &rd, &c), &g_err);
    memset(out, 0, sizeof *out);
    for (uint32_t i = 0; i < c.solver.num_roots; i++)
        hr_visit_leaves(&c.solver.roots[i], collect, out);
    il_hr_stats st = c.solver.stats;
    hr_print_stats(threads == 1 ? "1 thread" : "2 threads", &st);
    hr_case_free(&c);
    return st;
}

static void same_counts(const il_hr_stats *a, const il_hr_stats *b)
{
    CHECK(a->patches == b->patches);
    CHECK(a->elements == b->elements);
    CHECK(a->leaves == b->leaves);
    CHECK(a->links == b->links);
    CHECK(a->iterations == b->iterations);
    CHECK(a->visibility_rays == b->visibility_rays);
}

int main(void)
{
    il_scene *s = hr_room(false, false);
    il_light_desc pl = {.type = IL_LIGHT_POINT, .position = v3(0.8f, 0.7f, 0.3f),
                        .intensity = v3s(0.3f)};
    CHECK_OK(il_scene_add_light(s, &pl, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);

    leaves a, b, c;
    il_hr_stats sa = solve(s, 1, &a), sb = solve(s, 2, &b), sc = solve(s, 2, &c);
    same_counts(&sa, &sb);
    same_counts(&sb, &sc);
    CHECK(sa.elements > 1000 && sa.links > 10000 && sa.iterations > 1);
    CHECK(a.n == b.n && b.n == c.n);
    if (a.n == b.n && b.n == c.n) {
        CHECK(memcmp(a.rgb, b.rgb, a.n * sizeof *a.rgb) == 0);
        CHECK(memcmp(b.rgb, c.rgb, b.n * sizeof *b.rgb) == 0);
    }
    free(a.rgb), free(b.rgb), free(c.rgb);

    /* The whole method through il_bake: the same vertices and radiances. */
    il_bake_result *r1 = NULL, *r2 = NULL;
    il_hr_desc hd = {0};
    il_render_desc rd = {.method = IL_METHOD_HR, .threads = 1, .seed = 11, .hr = &hd};
    CHECK_OK(il_bake(s, &rd, &r1, &g_err), &g_err);
    rd.threads = 2;
    CHECK_OK(il_bake(s, &rd, &r2, &g_err), &g_err);
    if (r1 && r2) {
        CHECK(r1->num_meshes == r2->num_meshes);
        same_counts(&r1->stats.hr, &r2->stats.hr);
        for (uint32_t m = 0; m < r1->num_meshes && m < r2->num_meshes; m++) {
            CHECK(r1->meshes[m].num_vertices == r2->meshes[m].num_vertices);
            if (r1->meshes[m].num_vertices == r2->meshes[m].num_vertices)
                CHECK(memcmp(r1->meshes[m].radiance, r2->meshes[m].radiance,
                             3 * sizeof(float) * r1->meshes[m].num_vertices) == 0);
        }
    }
    il_bake_release(r1);
    il_bake_release(r2);
    il_scene_release(s);
    return check_report();
}
