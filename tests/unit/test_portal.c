/* Environment portals (scene/portal.h):
 * - which points a portal lights: those strictly on the side its front faces;
 * - segments entering and leaving by a portal, and where;
 *   crossings within 1e-3 of its plane's cosine count for nothing;
 * - directions through a rectangle of a x b seen on its axis from distance
 *   d: the mean of 1/pdf over them is the rectangle's solid angle,
 *   4 asin(ab / sqrt((a^2 + d^2)(b^2 + d^2))) (a, b the half-sides), and
 *   the pdf of each equals d'^2 / (A cos) for the point it aimed at;
 * - the pdf integrates to 1 over the sphere (uniform directions);
 * - the mixture with the environment (il_environment_sample_at) returns
 *   the density il_environment_pdf_at gives the same direction, and
 *   estimates the irradiance pi L of a uniform sky without bias; the light
 *   table's environment pdf is the mixture's times its selection;
 * - the light table's selection in a scene with portals: the sky by
 *   pi L A, a sun by E sum(A |cos|), lamps by their power, and a sun in
 *   the portals' plane still 5% of the total;
 * - il_scene_add_portal refuses NaN corners, slivers and a committed scene;
 * - JSON: "environment.portals" quads with a transform, "flip", errors. */
#include "scene_build.h"

#include "core/rng.h"
#include "core/sampling.h"
#include "scene/lights.h"
#include "scene/portal.h"
#include "scene/scene.h"

/* A floor under a uniform sky of radiance 1 and one portal: the rectangle
 * of half-sides 0.5 (x) and 0.75 (z) centred at (0, 2, 0), lighting the
 * side below it (its front faces -y).  Not committed. */
static il_scene *floor_sky_portal(void)
{
    il_scene *s = new_scene();
    add_quad(s, v3(0, -1, 0), v3(5, 0, 0), v3(0, 0, -5), 0);
    il_environment_desc env = {.radiance = v3s(1.0f)};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    /* Counter-clockwise seen from below. */
    il_vec3 c[6] = {v3(-0.5f, 2, -0.75f), v3(0.5f, 2, -0.75f), v3(0.5f, 2, 0.75f),
                    v3(-0.5f, 2, -0.75f), v3(0.5f, 2, 0.75f), v3(-0.5f, 2, 0.75f)};
    CHECK_OK(il_scene_add_portal(s, c, 2, &g_err), &g_err);
    return s;
}

static il_scene *portal_scene(void)
{
    il_scene *s = floor_sky_portal();
    commit(s);
    return s;
}

static void test_lit_side(const il_scene *s)
{
    CHECK(s->num_portals == 2);
    CHECK_NEAR(s->portals[0].n.y, -1.0, 1e-6);
    CHECK_NEAR(il_portal_area_seen(s, v3(0, 0, 0)), 1.5, 1e-6);
    CHECK_NEAR(il_portal_area_seen(s, v3(3, 1.9f, 7)), 1.5, 1e-6);
    CHECK(il_portal_area_seen(s, v3(0, 3, 0)) == 0.0f);
    CHECK(il_portal_area_seen(s, v3(0.2f, 2, 0.1f)) == 0.0f); /* on its plane */
    /* Seen from above, the environment is sampled as without portals. */
    il_vec3 d1, d2;
    float p1, p2;
    il_vec3 L1 = il_environment_sample_at(s, v3(0, 3, 0), v2(0.3f, 0.6f), &d1, &p1);
    il_vec3 L2 = il_environment_sample(s, v2(0.3f, 0.6f), &d2, &p2);
    CHECK(p1 == p2 && d1.x == d2.x && d1.y == d2.y && d1.z == d2.z && L1.x == L2.x);
}

/* Crossing the portal (lit side below, y < 2): a segment from above that
 * ends below enters, and one from below that ends above leaves, each at
 * its crossing; not when it ends on the plane within the margin, misses
 * the rectangle, or runs the other way. */
static void test_crossings(const il_scene *s)
{
    const float m = 1e-3f;
    float t = 0.0f;
    CHECK(il_portal_entered(s, v3(0.1f, 3, 0.2f), v3(0, -1, 0), 2.0f, m, &t));
    CHECK_NEAR(t, 1.0, 1e-5);
    CHECK(!il_portal_exited(s, v3(0.1f, 3, 0.2f), v3(0, -1, 0), 2.0f, m, NULL));
    CHECK(il_portal_exited(s, v3(0.1f, 1, 0.2f), v3(0, 1, 0), 2.0f, m, &t));
    CHECK_NEAR(t, 1.0, 1e-5);
    CHECK(!il_portal_entered(s, v3(0.1f, 1, 0.2f), v3(0, 1, 0), 2.0f, m, NULL));
    CHECK(!il_portal_exited(s, v3(0.1f, 1, 0.2f), v3(0, 1, 0), 1.0f, m, NULL));   /* ends on the plane */
    CHECK(!il_portal_exited(s, v3(0.9f, 1, 0.2f), v3(0, 1, 0), 2.0f, m, NULL));   /* beside it */
    CHECK(!il_portal_exited(s, v3(0.1f, 1, 0.2f), v3(0, 1, 0), 0.5f, m, NULL));   /* short of it */
}

/* A point a hair in front of the portal's plane sees it edge-on: such
 * crossings count for nothing (their density, squared by the power
 * heuristic, overflowed), draws through them fail, and the mixture's
 * densities stay finite. */
static void test_grazing(const il_scene *s)
{
    il_vec3 p = v3(3.0f, 2.0f - 1e-6f, 0.1f);
    float seen = il_portal_area_seen(s, p);
    CHECK(seen > 0.0f);
    int drawn = 0, finite = 0;
    for (int i = 0; i < 64; i++) {
        il_vec2 u = v2((i % 8 + 0.5f) / 8.0f, (i / 8 + 0.5f) / 8.0f);
        il_vec3 dir;
        drawn += il_portal_sample(s, p, seen, u, &dir);
        float pdf;
        il_environment_sample_at(s, p, u, &dir, &pdf);
        finite += isfinite(pdf) && isfinite(pdf * pdf);
    }
    CHECK(drawn == 0);
    CHECK(finite == 64);
    CHECK(il_portal_pdf(s, p, seen, v3_normalize(v3(-1.0f, 1e-6f, 0.0f))) == 0.0f);
}

static void test_solid_angle(const il_scene *s)
{
    const double a = 0.5, b = 0.75, d = 2.0;
    double omega = 4.0 * asin(a * b / sqrt((a * a + d * d) * (b * b + d * d)));
    il_vec3 p = v3(0, 0, 0);
    float seen = il_portal_area_seen(s, p);
    il_pcg32 rng = il_pcg32_seed(11, 0);
    const int n = 200000;
    double sum = 0.0;
    int bad = 0, off = 0;
    for (int i = 0; i < n; i++) {
        il_vec2 u = v2(il_pcg32_float(&rng), il_pcg32_float(&rng));
        il_vec3 dir;
        if (!il_portal_sample(s, p, seen, u, &dir)) {
            bad++;
            continue;
        }
        float pdf = il_portal_pdf(s, p, seen, dir);
        /* The point aimed at: on the plane y = 2, at distance 2 / dir.y. */
        double t = 2.0 / dir.y, want = t * t / (1.5 * dir.y);
        if (!(fabs(pdf - want) <= 1e-4 * want))
            off++;
        if (pdf > 0.0f)
            sum += 1.0 / pdf;
    }
    printf("portal solid angle: mean 1/pdf %.6f, exact %.6f (%d failed draws, %d pdfs off)\n",
           sum / n, omega, bad, off);
    CHECK(bad == 0);
    CHECK(off == 0);
    CHECK_REL(sum / n, omega, 2e-3);
}

static void test_pdf_normalised(const il_scene *s)
{
    il_vec3 p = v3(0.3f, 0.4f, -0.2f); /* off the axis */
    float seen = il_portal_area_seen(s, p);
    il_pcg32 rng = il_pcg32_seed(12, 0);
    const int n = 2000000;
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        il_vec3 dir = il_sample_uniform_sphere(v2(il_pcg32_float(&rng), il_pcg32_float(&rng)));
        sum += il_portal_pdf(s, p, seen, dir);
    }
    double integral = 4.0 * PI_D * sum / n;
    printf("portal pdf over the sphere: %.5f\n", integral);
    CHECK_NEAR(integral, 1.0, 0.01);
}

static void test_mixture(const il_scene *s)
{
    il_vec3 p = v3(0.2f, 0.0f, 0.1f);
    il_pcg32 rng = il_pcg32_seed(13, 0);
    const int n = 4000000;
    double e = 0.0;
    int through = 0, off = 0;
    for (int i = 0; i < n; i++) {
        il_vec2 u = v2(il_pcg32_float(&rng), il_pcg32_float(&rng));
        il_vec3 dir;
        float pdf;
        il_vec3 L = il_environment_sample_at(s, p, u, &dir, &pdf);
        if (!(pdf > 0.0f))
            continue;
        float want = il_environment_pdf_at(s, p, dir);
        if (!(fabsf(pdf - want) <= 1e-5f * want))
            off++;
        through += il_portal_pdf(s, p, il_portal_area_seen(s, p), dir) > 0.0f;
        if (dir.y > 0.0f)
            e += L.y * dir.y / pdf;
    }
    e /= n;
    printf("mixture: irradiance %.5f (pi %.5f), %.3f of draws through the portal, %d pdfs off\n",
           e, PI_D, (double)through / n, off);
    CHECK(off == 0);
    CHECK_REL(e, PI_D, 5e-3);
    /* The portal's share plus the environment's draws that happen to pass it. */
    CHECK((double)through / n > IL_PORTAL_SHARE);
    /* The light table's environment pdf: the selection times the mixture. */
    il_vec3 up = v3_normalize(v3(0.1f, 1.0f, 0.05f));
    CHECK_REL(il_light_pdf_environment(s, p, up),
              s->light_pmf[s->environment_light] * il_environment_pdf_at(s, p, up), 1e-6);
    CHECK(il_environment_pdf_at(s, p, up) > 10.0f * il_environment_pdf(s, up));
}

/* portal_scene's floor, sky and portal (1.5 m^2, facing -y) with a point
 * light of 0.5 W/sr (2 pi W) and a sun of irradiance 2 travelling along
 * `sun`. */
static il_scene *lit_portal_scene(il_vec3 sun)
{
    il_scene *s = floor_sky_portal();
    il_light_desc lamp = {.type = IL_LIGHT_POINT, .position = v3(0, 0, 0), .intensity = v3s(0.5f)};
    il_light_desc sn = {.type = IL_LIGHT_DIRECTIONAL, .direction = sun, .intensity = v3s(2.0f)};
    CHECK_OK(il_scene_add_light(s, &lamp, &g_err), &g_err);
    CHECK_OK(il_scene_add_light(s, &sn, &g_err), &g_err);
    commit(s);
    return s;
}

static void test_selection(void)
{
    il_scene *s = lit_portal_scene(v3(0.6f, -0.8f, 0.0f));
    double sky = PI_D * 1.5, lamp = 2.0 * PI_D, sun = 2.0 * 1.5 * 0.8, total = sky + lamp + sun;
    for (uint32_t i = 0; i < s->num_lights; i++) {
        il_light_kind k = s->lights[i].kind;
        double want = k == IL_LIGHTK_ENVIRONMENT ? sky : k == IL_LIGHTK_POINT ? lamp : sun;
        printf("selection: light %u (kind %d) %.5f, want %.5f\n", i, (int)k, (double)s->light_pmf[i],
               want / total);
        CHECK_REL(s->light_pmf[i], want / total, 1e-5);
    }
    il_scene_release(s);
    /* A sun in the portal's plane brings nothing in: it keeps 5% of the
     * total, so that what it lights outside is still sampled. */
    s = lit_portal_scene(v3(1.0f, 0.0f, 0.0f));
    total = sky + lamp;
    for (uint32_t i = 0; i < s->num_lights; i++)
        if (s->lights[i].kind == IL_LIGHTK_DIRECTIONAL)
            CHECK_REL(s->light_pmf[i], 0.05 * total / (1.05 * total), 1e-5);
    il_scene_release(s);
}

static void test_bad_portals(void)
{
    il_scene *s = new_scene();
    il_vec3 nan_tri[3] = {v3(0, 0, 0), v3(NAN, 0, 0), v3(0, 0, 1)};
    il_error e = {0};
    CHECK(il_scene_add_portal(s, nan_tri, 1, &e) == IL_ERR_INVALID);
    printf("NaN corner: %s\n", e.message);
    il_vec3 sliver[3] = {v3(0, 0, 0), v3(1, 0, 0), v3(2, 1e-7f, 0)};
    CHECK(il_scene_add_portal(s, sliver, 1, &e) == IL_ERR_INVALID);
    printf("sliver: %s\n", e.message);
    CHECK(il_scene_add_portal(s, NULL, 0, &e) == IL_ERR_INVALID);
    CHECK(s->num_portals == 0);
    add_quad(s, v3(0, 0, 0), v3(1, 0, 0), v3(0, 0, -1), 0);
    il_light_desc sun = {.type = IL_LIGHT_DIRECTIONAL, .direction = {0, -1, 0}, .intensity = {1, 1, 1}};
    CHECK_OK(il_scene_add_light(s, &sun, &g_err), &g_err);
    commit(s);
    il_vec3 ok[3] = {v3(0, 0, 0), v3(1, 0, 0), v3(0, 0, 1)};
    CHECK(il_scene_add_portal(s, ok, 1, &e) == IL_ERR_INVALID);
    il_scene_release(s);
}

static il_status load_json_text(const char *name, const char *text, il_scene **out, il_error *e)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", IL_TEST_TMP, name);
    mkdir(IL_TEST_TMP, 0755);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f)
        return IL_ERR_IO;
    fputs(text, f);
    fclose(f);
    return il_scene_load(path, NULL, out, e);
}

#define ROOM_JSON(portals)                                                                       \
    "{\"meshes\": [{\"shape\": \"quad\", \"size\": 4}],"                                          \
    " \"environment\": {\"sky\": \"overcast\", \"portals\": " portals "}}"

static void test_json(void)
{
    il_scene *s = NULL;
    il_error e = {0};
    /* A 2 x 1.2 m window in the wall z = 0, lighting the room at z < 0
     * (a quad faces +y; turned -90 degrees about x it faces -z). */
    CHECK_OK(load_json_text("portal_ok.json",
                            ROOM_JSON("[{\"shape\": \"quad\", \"size\": [2, 1.2], \"transform\": "
                                      "{\"translate\": [0, 1.5, 0], \"rotate\": [1, 0, 0, -90]}}]"),
                            &s, &e),
             &e);
    if (s) {
        il_scene_info in;
        il_scene_get_info(s, &in);
        CHECK(in.num_portal_triangles == 2);
        CHECK_NEAR(in.portal_area, 2.4, 1e-5);
        CHECK_NEAR(s->portals[0].n.z, -1.0, 1e-6);
        CHECK(il_portal_area_seen(s, v3(0, 1, -2)) > 0.0f && il_portal_area_seen(s, v3(0, 1, 2)) == 0.0f);
        il_scene_release(s);
        s = NULL;
    }
    /* "flip" turns it to light z > 0; inline triangles work too. */
    CHECK_OK(load_json_text("portal_flip.json",
                            ROOM_JSON("[{\"shape\": \"quad\", \"flip\": true, \"transform\": "
                                      "{\"rotate\": [1, 0, 0, -90]}},"
                                      " {\"positions\": [0,0,0, 1,0,0, 0,0,1], \"indices\": [0,2,1]}]"),
                            &s, &e),
             &e);
    if (s) {
        CHECK(s->num_portals == 3);
        CHECK_NEAR(s->portals[0].n.z, 1.0, 1e-6);
        CHECK_NEAR(s->portals[2].n.y, 1.0, 1e-6);
        il_scene_release(s);
        s = NULL;
    }
    const char *bad[] = {
        ROOM_JSON("[]"),
        ROOM_JSON("{\"shape\": \"quad\"}"),
        ROOM_JSON("[{\"shape\": \"box\"}]"),
        ROOM_JSON("[{\"size\": 2}]"),
        ROOM_JSON("[{\"positions\": [0,0,0, 1,0,0, 2,0,0]}]"),
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        CHECK(load_json_text("portal_bad.json", bad[k], &s, &e) != IL_OK);
        CHECK(s == NULL);
        printf("bad portal %zu: %s\n", k, e.message);
    }
}

int main(void)
{
    il_scene *s = portal_scene();
    test_lit_side(s);
    test_crossings(s);
    test_grazing(s);
    test_solid_angle(s);
    test_pdf_normalised(s);
    test_mixture(s);
    il_scene_release(s);
    test_selection();
    test_bad_portals();
    test_json();
    return check_report();
}
