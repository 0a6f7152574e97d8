/* Photon emission (methods/light_emit.c): every kind of light emits its analytic power
 * with the right distribution of directions, consistent with what the path
 * tracer receives from it (lights.c), and lights are chosen by power; with
 * portals, the portals' light (methods/portal_light.c) carries what enters
 * by them and the lights' paths stop where they enter; of them Linespace
 * keeps the portals' paths and the sun's that come in by a portal, never
 * the sky's own (il_portal_light_starts_inside), and draws no sky paths
 * (il_light_emit_inside). */
#include <string.h>

#include "scene_build.h"
#include "core/rng.h"
#include "methods/light_emit.h"
#include "methods/portal_light.h"
#include "scene/portal.h"
#include "scene/lights.h"
#include "trace/trace.h"

#define N_PHOTONS 200000

/* A floor 10 x 10 at y = -1, facing up: geometry for the scene's bounds. */
static void add_ground(il_scene *s)
{
    add_quad(s, v3(0, -1, 0), v3(0, 0, 5), v3(5, 0, 0), 0);
}

static void add_light(il_scene *s, il_light_desc d)
{
    CHECK_OK(il_scene_add_light(s, &d, &g_err), &g_err);
}

/* The ground under a uniform sky of radiance L; not committed. */
static il_scene *ground_under_sky(il_vec3 radiance)
{
    il_scene *s = new_scene();
    add_ground(s);
    il_environment_desc env = {.radiance = radiance};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    return s;
}

/* One emission; in a scene with portals, the light paths split there
 * (IL_PORTAL_LIGHT_SHARE_MAX of them from the portals), or with `inside`
 * as Linespace draws them (il_light_emit_inside, `share` from the portals). */
static bool emit_share(const il_scene *s, bool inside, float share, il_pcg32 *rng, il_light_emission *e)
{
    float u[IL_LIGHT_EMIT_DIMS];
    for (int i = 0; i < IL_LIGHT_EMIT_DIMS; i++)
        u[i] = il_pcg32_float(rng);
    return inside ? il_light_emit_inside(s, u, share, rng, 8, e) : il_light_emit(s, u, share, rng, 8, e);
}

static bool emit(const il_scene *s, il_pcg32 *rng, il_light_emission *e)
{
    return emit_share(s, false, IL_PORTAL_LIGHT_SHARE_MAX, rng, e);
}

/* Statistics of N photons. */
typedef struct stats {
    double power[3];     /* mean power (zero for failed emissions) */
    double mean_dir[3];
    double mean_cos;     /* mean dot(dir, axis) */
    double mean_abs_cos;
    double frac_near;    /* fraction of rays passing within r_near of `centre` */
    uint32_t failed;
    uint32_t outside;    /* dot(dir, axis) < min_cos - 1e-5 */
} stats;

static stats run(const il_scene *s, il_vec3 axis, float min_cos, il_vec3 centre, float r_near)
{
    stats st;
    memset(&st, 0, sizeof st);
    il_pcg32 rng = il_pcg32_seed(7, 11);
    for (int i = 0; i < N_PHOTONS; i++) {
        il_light_emission e;
        if (!emit(s, &rng, &e)) {
            st.failed++;
            continue;
        }
        st.power[0] += e.power.x;
        st.power[1] += e.power.y;
        st.power[2] += e.power.z;
        st.mean_dir[0] += e.dir.x;
        st.mean_dir[1] += e.dir.y;
        st.mean_dir[2] += e.dir.z;
        double c = v3_dot(e.dir, axis);
        st.mean_cos += c;
        st.mean_abs_cos += fabs(c);
        if (c < min_cos - 1e-5)
            st.outside++;
        /* Distance from centre to the ray's line. */
        il_vec3 d = v3_sub(centre, e.org);
        il_vec3 perp = v3_sub(d, v3_scale(e.dir, v3_dot(d, e.dir)));
        if (v3_length(perp) < r_near)
            st.frac_near += 1.0;
    }
    for (int c = 0; c < 3; c++) {
        st.power[c] /= N_PHOTONS;
        st.mean_dir[c] /= N_PHOTONS;
    }
    st.mean_cos /= N_PHOTONS;
    st.mean_abs_cos /= N_PHOTONS;
    st.frac_near /= N_PHOTONS;
    return st;
}

static void test_point(void)
{
    il_scene *s = new_scene();
    add_ground(s);
    add_light(s, (il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0, 1, 0),
                                 .intensity = v3(1, 2, 3)});
    commit(s);
    stats st = run(s, v3(0, 1, 0), -1.0f, v3(0, 0, 0), 0.0f);
    CHECK(st.failed == 0);
    CHECK_REL(st.power[0], 4 * PI_D * 1, 1e-5);
    CHECK_REL(st.power[1], 4 * PI_D * 2, 1e-5);
    CHECK_REL(st.power[2], 4 * PI_D * 3, 1e-5);
    /* Uniform over the sphere: mean direction 0, mean |cos| 1/2. */
    for (int c = 0; c < 3; c++)
        CHECK_NEAR(st.mean_dir[c], 0.0, 0.006);
    CHECK_NEAR(st.mean_abs_cos, 0.5, 0.004);
    il_scene_release(s);
}

/* Spot: power 2 pi I (1 - c^(n+1)) / (n+1), mean cos (n+1)/(n+2) (1 -
 * c^(n+2)) / (1 - c^(n+1)), and the intensity profile per solid angle
 * equals what il_light_sample_at gives the path tracer. */
static void test_spot(float angle, float n, float expect_cutoff_cos)
{
    il_scene *s = new_scene();
    add_ground(s);
    il_vec3 axis = v3_normalize(v3(0.3f, -1.0f, 0.2f));
    add_light(s, (il_light_desc){.type = IL_LIGHT_SPOT, .position = v3(0, 2, 0), .direction = axis,
                                 .intensity = v3(2, 1, 0.5f), .spot_angle = angle,
                                 .spot_exponent = n});
    commit(s);
    double cm = expect_cutoff_cos;
    double z = 2 * PI_D * (1 - pow(cm, n + 1)) / (n + 1);
    stats st = run(s, axis, (float)cm, v3(0, 0, 0), 0.0f);
    CHECK(st.failed == 0);
    CHECK(st.outside == 0);
    CHECK_REL(st.power[0], 2 * z, 1e-4);
    CHECK_REL(st.power[1], 1 * z, 1e-4);
    CHECK_REL(st.power[2], 0.5 * z, 1e-4);
    CHECK_NEAR(st.mean_cos, (n + 1) / (n + 2) * (1 - pow(cm, n + 2)) / (1 - pow(cm, n + 1)), 0.003);

    /* Intensity profile: photon power per solid angle in bins of cos theta
     * against the radiance * d^2 the path tracer receives at distance 1. */
    enum { BINS = 8 };
    double bin_power[BINS] = {0}, bin_count[BINS] = {0};
    il_pcg32 rng = il_pcg32_seed(3, 5);
    for (int i = 0; i < N_PHOTONS; i++) {
        il_light_emission e;
        if (!emit(s, &rng, &e))
            continue;
        double c = v3_dot(e.dir, axis);
        int b = (int)((c - cm) / (1 - cm) * BINS);
        if (b >= 0 && b < BINS) {
            bin_power[b] += e.power.x;
            bin_count[b] += 1;
        }
    }
    il_frame f = il_frame_from_normal(axis);
    for (int b = 0; b < BINS; b++) {
        double c0 = cm + (1 - cm) * b / BINS, c1 = cm + (1 - cm) * (b + 1) / BINS;
        double photon_i = bin_power[b] / N_PHOTONS / (2 * PI_D * (c1 - c0));
        double pt_i = 0;
        const int sub = 64;
        for (int k = 0; k < sub; k++) {
            double c = c0 + (c1 - c0) * (k + 0.5) / sub;
            double sn = sqrt(1 - c * c);
            il_vec3 d = il_frame_to_world(&f, v3((float)sn, 0, (float)c));
            il_light_sample ls;
            if (il_light_sample_at(s, v3_add(v3(0, 2, 0), d), 0.5f, v2(0.5f, 0.5f), &ls))
                pt_i += ls.radiance.x * ls.dist * ls.dist;
        }
        pt_i /= sub;
        /* Each photon of a bin carries the same power: the relative error
         * is about 1/sqrt(count); allow four of it. */
        CHECK_REL(photon_i, pt_i, fmax(0.02, 4.0 / sqrt(bin_count[b] + 1)));
    }
    il_scene_release(s);
}

static void test_area(bool two_sided)
{
    il_scene *s = new_scene();
    add_ground(s);
    il_vec3 le = v3(1.0f, 0.5f, 0.25f);
    uint32_t m = add_material(s, (il_material_desc){.emission = le, .two_sided = two_sided});
    /* 2 x 1 at y = 1, facing down: cross(ex, ey) = cross(x, z) = -y. */
    add_quad(s, v3(0, 1, 0), v3(1, 0, 0), v3(0, 0, 0.5f), m);
    commit(s);
    double a = 2.0, k = PI_D * a * (two_sided ? 2 : 1);
    il_vec3 nrm = v3(0, -1, 0);
    stats st = run(s, nrm, two_sided ? -1.0f : 0.0f, v3(0, 0, 0), 0.0f);
    CHECK(st.failed == 0);
    CHECK(st.outside == 0);
    CHECK_REL(st.power[0], 1.0 * k, 1e-4);
    CHECK_REL(st.power[1], 0.5 * k, 1e-4);
    CHECK_REL(st.power[2], 0.25 * k, 1e-4);
    /* Cosine emission: mean cos theta = 2/3 about the emitting face. */
    CHECK_NEAR(st.mean_abs_cos, 2.0 / 3.0, 0.003);
    CHECK_NEAR(st.mean_cos, two_sided ? 0.0 : 2.0 / 3.0, 0.006);

    /* Points on the quad, spread evenly, and the ray starts on the side it leaves by. */
    il_pcg32 rng = il_pcg32_seed(1, 2);
    uint32_t bad = 0, left = 0;
    for (int i = 0; i < 20000; i++) {
        il_light_emission e;
        if (!emit(s, &rng, &e))
            continue;
        if (fabsf(e.p.y - 1.0f) > 1e-5f || fabsf(e.p.x) > 1.0001f || fabsf(e.p.z) > 0.5001f)
            bad++;
        if (v3_dot(v3_sub(e.org, e.p), e.dir) <= 0.0f || fabsf(e.n.y + 1.0f) > 1e-5f)
            bad++;
        if (e.p.x < 0.0f)
            left++;
    }
    CHECK(bad == 0);
    CHECK_NEAR(left / 20000.0, 0.5, 0.015);
    il_scene_release(s);
}

/* Of 10,000 photons of a directional light, those whose origin is not on
 * the disk of radius R facing their direction outside the bounding
 * sphere. */
static uint32_t origins_off_disk(const il_scene *s)
{
    double r = s->scene_radius;
    il_pcg32 rng = il_pcg32_seed(9, 9);
    uint32_t bad = 0;
    for (int i = 0; i < 10000; i++) {
        il_light_emission e;
        emit(s, &rng, &e);
        il_vec3 d = v3_sub(e.org, s->scene_center);
        if (fabs(v3_dot(d, e.dir) + r) > 1e-4 * r || v3_length(d) > 1.4143 * r)
            bad++;
    }
    return bad;
}

/* Directional: a disk of radius R, so a quarter of the photons pass within
 * R/2 of the centre; power E pi R^2. */
static void test_directional(void)
{
    il_scene *s = new_scene();
    add_ground(s);
    il_vec3 dir = v3_normalize(v3(1, -2, 0.5f));
    add_light(s, (il_light_desc){.type = IL_LIGHT_DIRECTIONAL, .direction = dir,
                                 .intensity = v3(1, 2, 0.5f)});
    commit(s);
    double r = s->scene_radius;
    stats st = run(s, dir, 0.99999f, s->scene_center, (float)(0.5 * r));
    CHECK(st.failed == 0);
    CHECK(st.outside == 0);
    CHECK_REL(st.power[0], 1 * PI_D * r * r, 1e-4);
    CHECK_REL(st.power[1], 2 * PI_D * r * r, 1e-4);
    CHECK_NEAR(st.frac_near, 0.25, 0.004);
    CHECK(origins_off_disk(s) == 0);
    il_scene_release(s);
}

/* Directional with a disc of diameter D (half-angle a): directions
 * uniform over its cap (mean cos (1 + cos a) / 2), each photon's power
 * E pi R^2 2 / (1 + cos a) = L Omega pi R^2 for the disc's radiance
 * L = E / (pi sin^2 a); every origin on a disk of radius R facing its own
 * direction, outside the bounding sphere, so a quarter of the photons
 * still pass within R/2 of the centre. */
static void test_directional_disc(void)
{
    il_scene *s = new_scene();
    add_ground(s);
    il_vec3 dir = v3_normalize(v3(1, -2, 0.5f));
    add_light(s, (il_light_desc){.type = IL_LIGHT_DIRECTIONAL, .direction = dir,
                                 .intensity = v3(1, 2, 0.5f), .diameter = 20.0f});
    commit(s);
    double r = s->scene_radius, a = 10.0 * PI_D / 180.0;
    stats st = run(s, dir, (float)cos(a), s->scene_center, (float)(0.5 * r));
    CHECK(st.failed == 0);
    CHECK(st.outside == 0);
    CHECK_REL(st.power[0], PI_D * r * r * 2.0 / (1.0 + cos(a)), 1e-4);
    CHECK_NEAR(st.mean_cos, (1.0 + cos(a)) / 2.0, 2e-4);
    CHECK_NEAR(st.frac_near, 0.25, 0.004);
    CHECK(origins_off_disk(s) == 0);
    il_scene_release(s);
}

/* Environment: uniform directions, power 4 pi^2 R^2 L (lights.c), and the
 * flux through a sphere of radius R/2 is L 4 pi pi (R/2)^2: a quarter. */
static void test_environment(void)
{
    il_scene *s = ground_under_sky(v3(0.5f, 1, 2));
    commit(s);
    double r = s->scene_radius;
    stats st = run(s, v3(0, 1, 0), -1.0f, s->scene_center, (float)(0.5 * r));
    CHECK(st.failed == 0);
    double k = 4 * PI_D * PI_D * r * r;
    CHECK_REL(st.power[0], 0.5 * k, 1e-4);
    CHECK_REL(st.power[2], 2 * k, 1e-4);
    for (int c = 0; c < 3; c++)
        CHECK_NEAR(st.mean_dir[c], 0.0, 0.006);
    CHECK_NEAR(st.mean_abs_cos, 0.5, 0.004);
    CHECK_NEAR(st.frac_near, 0.25, 0.004);
    il_scene_release(s);
}

/* Two lights of power 1 : 3 (and an area light): photons split in
 * proportion to power, each light's share of the power is its own. */
static void test_split(void)
{
    il_scene *s = new_scene();
    add_ground(s);
    add_light(s, (il_light_desc){.type = IL_LIGHT_POINT, .position = v3(-1, 1, 0), .intensity = v3s(1)});
    add_light(s, (il_light_desc){.type = IL_LIGHT_POINT, .position = v3(1, 1, 0), .intensity = v3s(3)});
    /* An area light of power pi * 4 * 2 = 8 pi (8 : 4 pi : 12 pi). */
    uint32_t m = add_material(s, (il_material_desc){.emission = v3s(2)});
    add_quad(s, v3(0, 2, 0), v3(1, 0, 0), v3(0, 0, 1), m);
    commit(s);
    double phi[3] = {4 * PI_D, 12 * PI_D, 8 * PI_D}, total = phi[0] + phi[1] + phi[2];
    double count[3] = {0}, power[3] = {0};
    uint32_t unequal = 0;
    il_pcg32 rng = il_pcg32_seed(4, 4);
    for (int i = 0; i < N_PHOTONS; i++) {
        il_light_emission e;
        if (!emit(s, &rng, &e))
            continue;
        const il_light *l = &s->lights[e.light];
        int k = l->kind == IL_LIGHTK_AREA ? 2 : (l->position.x < 0 ? 0 : 1);
        count[k] += 1;
        power[k] += e.power.y;
        if (fabs(e.power.y - total) > 1e-4 * total)
            unequal++;
    }
    CHECK(unequal == 0);   /* every photon carries the same power */
    for (int k = 0; k < 3; k++) {
        CHECK_NEAR(count[k] / N_PHOTONS, phi[k] / total, 0.004);
        CHECK_REL(power[k] / N_PHOTONS, phi[k], 0.015);
    }
    il_scene_release(s);
}

/* ------------------------------------------------ portals (portal_light.c) */

/* The portal of test_portal.c: 1 x 1.5 at y = 2, lighting the side below
 * (its front faces -y); area 1.5. */
#define PORTAL_AREA 1.5
static void add_portal(il_scene *s)
{
    il_vec3 c[6] = {v3(-0.5f, 2, -0.75f), v3(0.5f, 2, -0.75f), v3(0.5f, 2, 0.75f),
                    v3(-0.5f, 2, -0.75f), v3(0.5f, 2, 0.75f), v3(-0.5f, 2, 0.75f)};
    CHECK_OK(il_scene_add_portal(s, c, 2, &g_err), &g_err);
}

/* Where the line of a photon crosses the portal's plane going down, inside
 * the portal: its distance along the ray (negative: behind the origin);
 * NAN when it does not. */
static double portal_crossing(const il_light_emission *e)
{
    if (!(e->dir.y < 0.0f))
        return NAN;
    double t = (2.0 - e->org.y) / e->dir.y;
    double x = e->org.x + t * e->dir.x, z = e->org.z + t * e->dir.z;
    return fabs(x) <= 0.5 && fabs(z) <= 0.75 ? t : NAN;
}

/* Under a uniform sky of radiance L with nothing above the portal, the
 * portals' light carries the flux L pi A that enters by it, from points on
 * the portal, downwards, none of it scattered; every environment photon
 * whose ray enters by the portal is stopped there; and the lights' share
 * of the photons still carries the environment's whole power. */
static void test_portal_light_environment(void)
{
    il_scene *s = ground_under_sky(v3(0.5f, 1, 2));
    add_portal(s);
    commit(s);
    CHECK(s->portal_light);
    /* Linespace's share from the portals: the sky alone, its most. */
    CHECK(il_portal_light_share(s) == IL_PORTAL_LIGHT_SHARE_MAX);
    double r = s->scene_radius, portal_flux = 0, lights_flux = 0;
    uint32_t portal = 0, bad = 0, entering = 0, stopped = 0, failed = 0;
    il_pcg32 rng = il_pcg32_seed(21, 3);
    for (int i = 0; i < N_PHOTONS; i++) {
        il_light_emission e;
        if (!emit(s, &rng, &e)) {
            failed++;
            continue;
        }
        CHECK(e.split);
        il_ray ray0 = {.org = e.org, .dir = e.dir, .tmax = INFINITY};
        /* Linespace keeps the portals' paths, never the sky's own. */
        bad += il_portal_light_starts_inside(s, &e, &ray0, INFINITY) != e.portal;
        if (e.portal) {
            portal++;
            portal_flux += e.power.y;
            /* Lifted off the portal's plane by the ray offset, upwards. */
            float lift = e.org.y - 2.0f;
            if (!(lift > 0.0f && lift < 10.0f * il_trace_epsilon(s->tracer)) ||
                fabsf(e.org.x) > 0.5001f || fabsf(e.org.z) > 0.7501f || !(e.dir.y < 0.0f) ||
                e.scattered || e.caustic)
                bad++;
            continue;
        }
        lights_flux += e.power.y;
        /* Stopped where it enters (the floor below ends the ray), and only then. */
        double t = portal_crossing(&e);
        il_ray ray = {.org = e.org, .dir = e.dir, .tmax = INFINITY};
        float t_end = e.dir.y < 0.0f ? (-1.0f - e.org.y) / e.dir.y : INFINITY, tc = 0;
        bool stops = il_portal_light_stops(s, &e, 0, &ray, t_end, &tc);
        if (t > 0) {
            entering++;
            stopped += stops && fabs(tc - t) < 1e-4 * r;
        } else if (stops) {
            bad++;
        }
    }
    CHECK(bad == 0);
    CHECK(failed < N_PHOTONS / 1000);      /* grazing draws and misses of the map */
    CHECK(entering > 0 && stopped == entering);
    CHECK_NEAR((double)portal / N_PHOTONS, IL_PORTAL_LIGHT_SHARE_MAX, 0.004);
    CHECK_REL(portal_flux / N_PHOTONS, 1.0 * PI_D * PORTAL_AREA, 0.01);
    CHECK_REL(lights_flux / N_PHOTONS, 4 * PI_D * PI_D * r * r, 0.02);
    il_scene_release(s);
}

/* The sun straight down on the portal: its photons are drawn through the
 * portal in most cases (p_disk / p_mixture weights), and the flux of those
 * whose line crosses it is E A, the whole still E pi R^2; its direct light
 * entering is not stopped, the same ray after a bounce is. */
static void test_portal_directional(void)
{
    il_scene *s = new_scene();
    add_ground(s);
    add_light(s, (il_light_desc){.type = IL_LIGHT_DIRECTIONAL, .direction = v3(0, -1, 0),
                                 .intensity = v3s(2.0f)});
    add_portal(s);
    commit(s);
    double r = s->scene_radius, through = 0, total = 0;
    uint32_t lights = 0, crossing = 0, stopped_direct = 0, stopped_after = 0, inside_wrong = 0;
    il_pcg32 rng = il_pcg32_seed(5, 8);
    for (int i = 0; i < N_PHOTONS; i++) {
        il_light_emission e;
        if (!emit(s, &rng, &e) || e.portal)
            continue;       /* no environment: the portals' light sees only darkness */
        lights++;
        total += e.power.x;
        double t = portal_crossing(&e);
        il_ray ray = {.org = e.org, .dir = e.dir, .tmax = INFINITY};
        float t_end = (-1.0f - e.org.y) / e.dir.y;
        /* Linespace keeps the sun's paths that come in by the window alone. */
        inside_wrong += il_portal_light_starts_inside(s, &e, &ray, t_end) != (t > 0);
        if (!(t > 0))
            continue;
        crossing++;
        through += e.power.x;
        stopped_direct += il_portal_light_stops(s, &e, 0, &ray, t_end, NULL);
        stopped_after += il_portal_light_stops(s, &e, 1, &ray, t_end, NULL);
    }
    double lights_share = 1.0 - IL_PORTAL_LIGHT_SHARE_MAX;
    CHECK_NEAR((double)lights / N_PHOTONS, lights_share, 0.004);
    /* IL_PORTAL_SHARE of them aimed at the portal, and a few more from the disk. */
    CHECK((double)crossing / lights > IL_PORTAL_SHARE && (double)crossing / lights < IL_PORTAL_SHARE + 0.01);
    CHECK_REL(through / N_PHOTONS, 2.0 * PORTAL_AREA, 0.01);
    CHECK_REL(total / N_PHOTONS, 2.0 * PI_D * r * r, 0.03);
    CHECK(stopped_direct == 0);
    CHECK(stopped_after == crossing);
    CHECK(inside_wrong == 0);
    il_scene_release(s);
}

/* Light reaching the portal from a surface outside: a sun from below
 * lights the underside of a roof 1 above the portal (albedo rho, so it
 * sends L = rho E / pi down); the portals' light carries rho E A F by it
 * (F the roof's view factor from the portal, 1 - 3e-6 for a roof of
 * half-side 1000), every photon of it scattered, none a caustic one. */
static void test_portal_light_scattered(void)
{
    il_scene *s = new_scene();
    const float rho = 0.5f, e_sun = 3.0f;
    uint32_t m = add_material(s, (il_material_desc){.diffuse = v3s(rho)});
    add_quad(s, v3(0, 3, 0), v3(1000, 0, 0), v3(0, 0, 1000), m);   /* faces -y */
    add_light(s, (il_light_desc){.type = IL_LIGHT_DIRECTIONAL, .direction = v3(0, 1, 0),
                                 .intensity = v3s(e_sun)});
    add_portal(s);
    commit(s);
    double flux = 0;
    uint32_t bad = 0;
    il_pcg32 rng = il_pcg32_seed(9, 1);
    for (int i = 0; i < N_PHOTONS; i++) {
        il_light_emission e;
        if (!emit(s, &rng, &e) || !e.portal)
            continue;
        flux += e.power.x;
        bad += !e.scattered || e.caustic || e.rays < 2;
    }
    CHECK(bad == 0);
    CHECK_REL(flux / N_PHOTONS, rho * e_sun * PORTAL_AREA, 0.01);
    il_scene_release(s);
}

/* il_light_emit_inside (Linespace): under a sky alone every path starts
 * at the portal and still carries L pi A; with a lamp inside too, the
 * lights' paths all leave the lamp, which carries its power on average,
 * and the portal's paths keep their share and flux. */
static void test_emit_inside(void)
{
    for (int with_lamp = 0; with_lamp < 2; with_lamp++) {
        il_scene *s = ground_under_sky(v3s(0.5f));
        if (with_lamp)
            add_light(s, (il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0, 1, 0),
                                         .intensity = v3s(3.0f)});
        add_portal(s);
        commit(s);
        float share = il_portal_light_share(s);
        double portal_flux = 0, lamp_flux = 0;
        uint32_t portal = 0, lamp = 0, sky = 0;
        il_pcg32 rng = il_pcg32_seed(31, 5);
        for (int i = 0; i < N_PHOTONS; i++) {
            il_light_emission e;
            if (!emit_share(s, true, share, &rng, &e))
                continue;
            if (e.portal) {
                portal++;
                portal_flux += e.power.y;
            } else if (s->lights[e.light].kind == IL_LIGHTK_POINT) {
                lamp++;
                lamp_flux += e.power.y;
            } else {
                sky++;
            }
        }
        printf("emit inside%s: %u from the portal, %u from the lamp, %u from the sky\n",
               with_lamp ? " with a lamp" : "", portal, lamp, sky);
        CHECK(sky == 0);
        CHECK_NEAR((double)portal / N_PHOTONS, with_lamp ? share : 1.0, 0.004);
        CHECK_REL(portal_flux / N_PHOTONS, 0.5 * PI_D * PORTAL_AREA, 0.01);
        if (with_lamp) {
            CHECK(lamp + portal > N_PHOTONS - N_PHOTONS / 100);
            CHECK_REL(lamp_flux / N_PHOTONS, 4 * PI_D * 3.0, 0.02);
        }
        il_scene_release(s);
    }
}

/* Which lamps' paths Linespace keeps (il_portal_light_starts_inside): a
 * lamp below the portal, on its lit side, is inside and keeps every path,
 * as does a panel beside the portal in its plane shining down (a lamp in
 * the window wall); a street lamp above it keeps the paths that come in
 * by the portal. */
static void test_portal_lamps_inside(void)
{
    il_scene *s = ground_under_sky(v3s(0.5f));
    add_light(s, (il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0, 1, 0), .intensity = v3s(3.0f)});
    add_light(s, (il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0, 4, 0), .intensity = v3s(3.0f)});
    uint32_t lamp = add_material(s, (il_material_desc){.emission = v3s(2.0f)});
    add_quad(s, v3(1.5f, 2, 0), v3(0.4f, 0, 0), v3(0, 0, 0.4f), lamp);   /* faces -y */
    add_portal(s);
    commit(s);
    uint32_t inside = 0, street = 0, street_in = 0, panel = 0, wrong = 0;
    il_pcg32 rng = il_pcg32_seed(21, 4);
    for (int i = 0; i < N_PHOTONS; i++) {
        il_light_emission e;
        if (!emit(s, &rng, &e) || e.portal)
            continue;
        il_light_kind kind = s->lights[e.light].kind;
        if (kind != IL_LIGHTK_POINT && kind != IL_LIGHTK_AREA)
            continue;
        il_ray ray = {.org = e.org, .dir = e.dir, .tmax = INFINITY};
        float t_end = e.dir.y < 0.0f ? (-1.0f - e.org.y) / e.dir.y : INFINITY;
        bool kept = il_portal_light_starts_inside(s, &e, &ray, t_end);
        if (kind == IL_LIGHTK_AREA) {
            panel++;
            wrong += !kept;
        } else if (e.p.y < 2.0f) {
            inside++;
            wrong += !kept;
        } else {
            street++;
            street_in += kept;
            wrong += kept != (portal_crossing(&e) > 0);
        }
    }
    printf("lamps' paths kept: inside %u, the panel %u, the street lamp %u of %u; %u wrong\n", inside, panel,
           street_in, street, wrong);
    CHECK(wrong == 0);
    CHECK(inside > 1000 && panel > 1000 && street > 1000 && street_in > 0 && street_in < street / 4);
    il_scene_release(s);
}

/* The lights' share of split paths: a lamp inside and the sky.  The
 * scene's table weighs the sky by what it brings in by the portal
 * (scene/lights.c), not by its power over the scene's bounding disk: the
 * lamp gets its share of the lights' photons by that table, and each
 * light's photons still carry its own power on average. */
static void test_portal_light_choice(void)
{
    il_scene *s = ground_under_sky(v3s(0.5f));
    add_light(s, (il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0, 1, 0), .intensity = v3s(3.0f)});
    add_portal(s);
    commit(s);
    double r = s->scene_radius, lamp_power = 4 * PI_D * 3.0, sky_power = 4 * PI_D * PI_D * r * r * 0.5;
    double lamp_flux = 0, sky_flux = 0;
    uint32_t lamp = 0, lights = 0;
    il_pcg32 rng = il_pcg32_seed(13, 2);
    for (int i = 0; i < N_PHOTONS; i++) {
        il_light_emission e;
        if (!emit(s, &rng, &e) || e.portal)
            continue;
        lights++;
        if (s->lights[e.light].kind == IL_LIGHTK_POINT) {
            lamp++;
            lamp_flux += e.power.y;
        } else {
            sky_flux += e.power.y;
        }
    }
    /* The powers are luminances of these grey lights; the sky weighs
     * pi L A, A the portal's area. */
    double w_lamp = lamp_power, w_sky = PI_D * 0.5 * PORTAL_AREA;
    uint32_t li = s->lights[0].kind == IL_LIGHTK_POINT ? 0 : 1;
    printf("lights' share: the lamp %.4f of the lights' photons, its table entry %.4f (by power %.4f)\n",
           (double)lamp / lights, (double)s->light_pmf[li], lamp_power / (lamp_power + sky_power));
    CHECK_REL(s->light_pmf[li], w_lamp / (w_lamp + w_sky), 1e-5);
    /* The lamp outweighs the sky 16 to 1: Linespace's share from the
     * portals is its least. */
    CHECK(il_portal_light_share(s) == 1.0f - IL_PORTAL_LIGHT_SHARE_MAX);
    CHECK_NEAR((double)lamp / lights, w_lamp / (w_lamp + w_sky), 0.01);
    CHECK_REL(lamp_flux / N_PHOTONS, lamp_power, 0.02);
    CHECK_REL(sky_flux / N_PHOTONS, sky_power, 0.03);
    il_scene_release(s);
}

int main(void)
{
    test_point();
    test_spot(30.0f, 5.0f, (float)cos(30.0 * PI_D / 180.0));
    test_spot(60.0f, 0.0f, (float)cos(60.0 * PI_D / 180.0));
    test_spot(120.0f, 0.0f, (float)cos(120.0 * PI_D / 180.0));   /* wider than a hemisphere */
    test_spot(120.0f, 2.0f, 0.0f);   /* cos^n ends at 90 degrees */
    test_area(false);
    test_area(true);
    test_directional();
    test_directional_disc();
    test_environment();
    test_split();
    test_portal_light_environment();
    test_portal_directional();
    test_portal_light_scattered();
    test_portal_light_choice();
    test_portal_lamps_inside();
    test_emit_inside();
    return check_report();
}
