/* Photon tracing (pm_trace.c): the same photons for any thread count, the
 * energy balance of a closed box, caustic/global classification, and no
 * photons where nothing is lit. */
#include <string.h>

#include "scene_build.h"
#include "methods/photon/pm.h"
#include "scene/scene.h"


/* ------------------------------------------------------- deposit records */

typedef struct record {
    uint64_t count, caustic;
    double power[3];
    double caustic_power[3];
    double radial;          /* sum of the distance to the y axis */
    uint64_t wrong_side;    /* n or wi facing away from `inside` */
    uint64_t off_power;     /* power differs from `expect` */
    il_vec3 inside;         /* a point on the lit side, when check_side */
    bool check_side;
    double expect;          /* > 0: every deposit's power.x should equal it */
    double min_y, max_y;
} record;

static void on_deposit(void *user, const il_pm_deposit *d)
{
    record *r = user;
    r->count++;
    r->power[0] += d->power.x;
    r->power[1] += d->power.y;
    r->power[2] += d->power.z;
    if (d->caustic) {
        r->caustic++;
        r->caustic_power[0] += d->power.x;
    }
    r->radial += sqrt((double)d->p.x * d->p.x + (double)d->p.z * d->p.z);
    r->min_y = fmin(r->min_y, d->p.y);
    r->max_y = fmax(r->max_y, d->p.y);
    if (fabsf(v3_length(d->wi) - 1.0f) > 1e-4f || v3_dot(d->wi, d->n) <= 0.0f)
        r->wrong_side++;
    if (r->check_side && v3_dot(v3_sub(r->inside, d->p), d->n) <= 0.0f)
        r->wrong_side++;
    if (r->expect > 0 && fabs(d->power.x - r->expect) > 1e-4 * r->expect)
        r->off_power++;
}

static record trace_all(const il_scene *s, uint64_t n, uint32_t max_depth, uint64_t *rays)
{
    record r;
    memset(&r, 0, sizeof r);
    r.min_y = INFINITY;
    r.max_y = -INFINITY;
    *rays = 0;
    for (uint64_t i = 0; i < n; i++)
        *rays += il_pm_trace_photon(s, 42, i, max_depth, false, on_deposit, &r);
    return r;
}

/* Same record, filled after the fact (power and the expectations set). */
static record trace_expect(const il_scene *s, uint64_t n, uint32_t max_depth, double expect,
                           uint64_t *rays)
{
    record r;
    memset(&r, 0, sizeof r);
    r.min_y = INFINITY;
    r.max_y = -INFINITY;
    r.expect = expect;
    *rays = 0;
    for (uint64_t i = 0; i < n; i++)
        *rays += il_pm_trace_photon(s, 42, i, max_depth, false, on_deposit, &r);
    return r;
}

/* ---------------------------------------------------------------- tests */

/* (a) The arrays are byte for byte the same with 1 and 2 threads, and a
 * trace split in two index ranges is the same as one trace. */
static void test_determinism(void)
{
    il_scene *s = NULL;
    CHECK_OK(il_scene_load("cornell", NULL, &s, &g_err), &g_err);
    if (!s)
        return;
    commit(s);
    il_pm_trace_desc d = {.first = 0, .count = 30000, .seed = 5, .max_depth = 16, .threads = 1,
                          .split = true};
    il_pm_photons a, b, c1, c2;
    CHECK_OK(il_pm_trace(s, &d, &a, &g_err), &g_err);
    d.threads = 2;
    CHECK_OK(il_pm_trace(s, &d, &b, &g_err), &g_err);
    CHECK(a.num_global > 20000);
    CHECK(a.num_global == b.num_global && a.num_caustic == b.num_caustic && a.rays == b.rays);
    CHECK(a.rays >= d.count);
    if (a.num_global == b.num_global)
        CHECK(memcmp(a.global, b.global, a.num_global * sizeof(il_photon)) == 0);
    if (a.num_caustic == b.num_caustic && a.num_caustic)
        CHECK(memcmp(a.caustic, b.caustic, a.num_caustic * sizeof(il_photon)) == 0);

    /* [0, 10000) then [10000, 30000), 2 threads. */
    d.count = 10000;
    CHECK_OK(il_pm_trace(s, &d, &c1, &g_err), &g_err);
    d.first = 10000;
    d.count = 20000;
    CHECK_OK(il_pm_trace(s, &d, &c2, &g_err), &g_err);
    CHECK(c1.num_global + c2.num_global == a.num_global);
    CHECK(c1.rays + c2.rays == a.rays);
    if (c1.num_global + c2.num_global == a.num_global) {
        CHECK(memcmp(a.global, c1.global, c1.num_global * sizeof(il_photon)) == 0);
        CHECK(memcmp(a.global + c1.num_global, c2.global, c2.num_global * sizeof(il_photon)) == 0);
    }
    free(a.global), free(a.caustic), free(b.global), free(b.caustic);
    free(c1.global), free(c1.caustic), free(c2.global), free(c2.caustic);

    /* No photons asked: nothing, and no error. */
    d.count = 0;
    CHECK_OK(il_pm_trace(s, &d, &a, &g_err), &g_err);
    CHECK(a.num_global == 0 && a.num_caustic == 0 && a.global == NULL && a.rays == 0);
    il_scene_release(s);
}

/* (b) A closed box of Lambertian albedo rho lit from inside: the first hit
 * is not stored, the k-th later one carries Phi rho^(k-1) on average, so
 * the stored power per photon is Phi rho / (1 - rho) per channel (the
 * radiosity furnace, Jensen 2001 5.2). */
static void test_energy(void)
{
    il_scene *s = new_scene();
    const double rho[3] = {0.3, 0.5, 0.7};
    uint32_t m = add_material(s, (il_material_desc){.diffuse = v3(0.3f, 0.5f, 0.7f)});
    /* Faces of the cube [-1,1]^3 facing in, slightly oversized so the
     * edges overlap and leave no crack. */
    const float h = 1.01f;
    add_quad(s, v3(0, -1, 0), v3(h, 0, 0), v3(0, 0, -h), m);  /* floor, +y */
    add_quad(s, v3(0, 1, 0), v3(h, 0, 0), v3(0, 0, h), m);    /* ceiling, -y */
    add_quad(s, v3(-1, 0, 0), v3(0, 0, h), v3(0, -h, 0), m);  /* +x */
    add_quad(s, v3(1, 0, 0), v3(0, 0, h), v3(0, h, 0), m);    /* -x */
    add_quad(s, v3(0, 0, -1), v3(0, h, 0), v3(-h, 0, 0), m);  /* +z */
    add_quad(s, v3(0, 0, 1), v3(0, h, 0), v3(h, 0, 0), m);    /* -z */
    il_light_desc l = {.type = IL_LIGHT_POINT, .position = v3(0.2f, 0.1f, -0.3f), .intensity = v3s(1)};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    commit(s);
    const double phi = 4 * PI_D;
    const uint64_t n = 100000;

    record r;
    memset(&r, 0, sizeof r);
    r.check_side = true;
    r.inside = v3(0, 0, 0);
    uint64_t rays = 0;
    for (uint64_t i = 0; i < n; i++)
        rays += il_pm_trace_photon(s, 42, i, 100000, false, on_deposit, &r);
    for (int c = 0; c < 3; c++)
        CHECK_REL(r.power[c] / n, phi * rho[c] / (1 - rho[c]), 0.02);
    CHECK(r.caustic == 0);
    CHECK(r.wrong_side == 0);
    /* One ray per hit: the hits are the deposits and the first ones. */
    CHECK(rays == r.count + n);

    /* The same through il_pm_trace and the packed photons. */
    il_pm_trace_desc d = {.count = n, .seed = 42, .max_depth = 100000, .threads = 2, .split = true};
    il_pm_photons ph;
    CHECK_OK(il_pm_trace(s, &d, &ph, &g_err), &g_err);
    CHECK(ph.num_global == r.count && ph.num_caustic == 0 && ph.rays == rays);
    double sum[3] = {0};
    for (size_t i = 0; i < ph.num_global; i++) {
        il_vec3 p = il_photon_power(&ph.global[i]);
        sum[0] += p.x, sum[1] += p.y, sum[2] += p.z;
    }
    for (int c = 0; c < 3; c++)
        CHECK_REL(sum[c] / n, r.power[c] / n, 0.01);
    free(ph.global);
    free(ph.caustic);

    /* A depth cap of 2 bounces stores Phi (rho + rho^2). */
    memset(&r, 0, sizeof r);
    for (uint64_t i = 0; i < n; i++)
        il_pm_trace_photon(s, 42, i, 2, false, on_deposit, &r);
    for (int c = 0; c < 3; c++)
        CHECK_REL(r.power[c] / n, phi * (rho[c] + rho[c] * rho[c]), 0.02);
    il_scene_release(s);
}

/* (c) A spot light aimed up at a mirror over a black floor: every photon on
 * the floor is caustic and carries the mirror's reflectance; a diffuse
 * ceiling instead gives global photons only. */
static void test_mirror(bool mirror)
{
    il_scene *s = new_scene();
    uint32_t black = add_material(s, (il_material_desc){.diffuse = v3s(0)});
    uint32_t top = add_material(s, mirror ? (il_material_desc){.type = IL_MATERIAL_MIRROR,
                                                               .specular = v3s(0.9f)}
                                          : (il_material_desc){.diffuse = v3s(0.9f)});
    add_quad(s, v3(0, 0, 0), v3(0, 0, 50), v3(50, 0, 0), black);  /* floor, +y */
    add_quad(s, v3(0, 2, 0), v3(1, 0, 0), v3(0, 0, 1), top);      /* ceiling, -y */
    il_light_desc l = {.type = IL_LIGHT_SPOT, .position = v3(0, 1, 0), .direction = v3(0, 1, 0),
                       .intensity = v3s(1), .spot_angle = 10.0f};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    commit(s);
    const uint64_t n = 50000;
    const double phi = 2 * PI_D * (1 - cos(10 * PI_D / 180));
    uint64_t rays;
    record r = trace_expect(s, n, 10, phi, &rays);
    CHECK(r.count > n / 2);
    CHECK(r.min_y > -1e-3 && r.max_y < 1e-3);   /* only on the floor */
    CHECK(r.wrong_side == 0);
    if (mirror) {
        CHECK(r.caustic == r.count);
        CHECK(r.off_power == 0);                 /* q = 0.9: power kept as it is */
        CHECK_REL(r.power[0] / n, 0.9 * phi, 0.01);
        /* Reflected about y = 2 from y = 1: the beam lands within 3 tan(10) of the axis. */
        CHECK(r.radial / r.count < 3 * tan(10 * PI_D / 180));
    } else {
        CHECK(r.caustic == 0);
        CHECK_REL(r.power[0] / n, 0.9 * phi, 0.03);  /* nearly all of the hemisphere reaches the floor */
    }
    il_scene_release(s);
}

/* (c) A glass ball (a ball lens, focus n R / (2 (n - 1)) = 1.5 R from its
 * centre) between a narrow spot and a black floor at its focus: the
 * photons it refracts onto the floor are caustic, gathered near the axis,
 * and a photon that passes in and out of the glass keeps its power (flux
 * does not take radiance's 1/eta^2). */
static void test_glass(void)
{
    il_scene *s = new_scene();
    uint32_t black = add_material(s, (il_material_desc){.diffuse = v3s(0)});
    uint32_t glass = add_material(s, (il_material_desc){.type = IL_MATERIAL_DIELECTRIC, .ior = 1.5f});
    add_quad(s, v3(0, 0.5f, 0), v3(0, 0, 20), v3(20, 0, 0), black);
    add_ball(s, v3(0, 2, 0), 1.0f, glass);
    double half = atan(0.5 / 8.0) * 180 / PI_D;   /* a beam of radius 0.5 at the ball */
    il_light_desc l = {.type = IL_LIGHT_SPOT, .position = v3(0, 10, 0), .direction = v3(0, -1, 0),
                       .intensity = v3s(1), .spot_angle = (float)half};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    commit(s);
    const uint64_t n = 50000;
    const double phi = 2 * PI_D * (1 - cos(half * PI_D / 180));
    uint64_t rays;
    record r = trace_expect(s, n, 20, phi, &rays);
    CHECK(r.count > n * 8 / 10);                /* ~92% pass two interfaces */
    CHECK(r.caustic == r.count);
    CHECK(r.off_power == 0);
    CHECK(r.wrong_side == 0);
    CHECK(r.max_y < 0.5 + 1e-3);
    /* Without the ball the beam is 0.59 wide at the floor (mean radius
     * ~0.4); the lens gathers it near the axis. */
    CHECK(r.radial / r.count < 0.12);
    /* Fresnel transmission at normal-ish incidence, twice: 0.96^2. */
    CHECK_REL(r.power[0] / n, 0.92 * phi, 0.04);

    /* split: caustic photons to the caustic map; split off: all global. */
    il_pm_trace_desc d = {.count = 20000, .seed = 1, .max_depth = 20, .threads = 2, .split = true};
    il_pm_photons a, b;
    CHECK_OK(il_pm_trace(s, &d, &a, &g_err), &g_err);
    d.split = false;
    CHECK_OK(il_pm_trace(s, &d, &b, &g_err), &g_err);
    CHECK(a.num_global == 0 && a.num_caustic > 15000);
    CHECK(b.num_caustic == 0 && b.num_global == a.num_caustic);
    if (b.num_global == a.num_caustic)
        CHECK(memcmp(a.caustic, b.global, a.num_caustic * sizeof(il_photon)) == 0);
    free(a.global), free(a.caustic), free(b.global), free(b.caustic);
    il_scene_release(s);
}

/* (d) Lights that face away from all geometry store nothing: one ray each. */
static void test_away(void)
{
    il_scene *s = new_scene();
    uint32_t white = add_material(s, (il_material_desc){.diffuse = v3s(0.8f)});
    uint32_t emit = add_material(s, (il_material_desc){.emission = v3s(5)});
    add_quad(s, v3(0, 0, 0), v3(0, 0, 5), v3(5, 0, 0), white);       /* floor, +y */
    add_quad(s, v3(0, 1, 0), v3(0, 0, 0.5f), v3(0.5f, 0, 0), emit);  /* emitter facing +y */
    il_light_desc l = {.type = IL_LIGHT_SPOT, .position = v3(2, 0.5f, 0), .direction = v3(0, 1, 0),
                       .intensity = v3s(3), .spot_angle = 60.0f};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    commit(s);
    uint64_t rays;
    record r = trace_all(s, 20000, 10, &rays);
    CHECK(r.count == 0);
    CHECK(rays == 20000);
    il_pm_trace_desc d = {.count = 20000, .seed = 3, .max_depth = 10, .threads = 2, .split = true};
    il_pm_photons a;
    CHECK_OK(il_pm_trace(s, &d, &a, &g_err), &g_err);
    CHECK(a.num_global == 0 && a.num_caustic == 0 && a.global == NULL && a.caustic == NULL);
    CHECK(a.rays == 20000);
    il_scene_release(s);
}

int main(void)
{
    test_determinism();
    test_energy();
    test_mirror(true);
    test_mirror(false);
    test_glass();
    test_away();
    return check_report();
}
