/* il_rad_direct against closed forms: the irradiance it puts on each patch,
 * recovered as E = pi (direct - Le) / rho, against
 * - a point light: E = I cos(theta) / d^2, integrated over the patch
 *   numerically (and at the patch below the light, I / h^2 within 1%);
 * - a spot light: the same inside its cone times cos^n, zero outside;
 * - a directional light and a uniform sky over an open floor:
 *   E = E_l cos(theta) + pi L_sky;
 * - shadows: a patch behind an occluder gets nothing from the light. */
#include "rad_scenes.h"

/* Mean over the axis-aligned floor patch [x0,x1] x [z0,z1] (y = 0) of
 * I cos(theta)/d^2 from a point light at q, times the spot profile when
 * spot_n >= 0 (axis straight down, cut-off cos_cut). */
static double floor_irradiance(double x0, double x1, double z0, double z1, il_vec3 q, double I,
                               double spot_n, double cos_cut)
{
    const int n = 200;
    double sum = 0.0;
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            double x = x0 + (x1 - x0) * (a + 0.5) / n, z = z0 + (z1 - z0) * (b + 0.5) / n;
            double dx = q.x - x, dy = q.y, dz = q.z - z;
            double d2 = dx * dx + dy * dy + dz * dz, d = sqrt(d2);
            double cosr = dy / d;
            double e = I * cosr / d2;
            if (spot_n >= 0.0) {
                if (cosr < cos_cut)
                    e = 0.0;
                else if (spot_n > 0.0)
                    e *= pow(cosr, spot_n);
            }
            sum += e;
        }
    return sum / ((double)n * n);
}

static void patch_bounds(const il_patch_mesh *m, const il_patch *p, double *x0, double *x1,
                         double *z0, double *z1)
{
    *x0 = *z0 = 1e30;
    *x1 = *z1 = -1e30;
    for (uint32_t k = 0; k < p->num_corners; k++) {
        il_vec3 v = m->positions[p->v[k]];
        *x0 = fmin(*x0, v.x);
        *x1 = fmax(*x1, v.x);
        *z0 = fmin(*z0, v.z);
        *z1 = fmax(*z1, v.z);
    }
}

static void test_point_and_spot(bool spot)
{
    const float rho = 0.5f, I = 10.0f;
    il_scene *s = new_scene();
    uint32_t grey = diffuse_material(s, v3s(rho), v3s(0));
    const uint32_t mat[6] = {grey, grey, grey, grey, grey, grey};
    add_box_room(s, 2.0f, mat);
    /* Above the centre of the floor patch [1, 1.25]^2 (8 x 8 patches). */
    il_vec3 q = v3(1.125f, 1.8f, 1.125f);
    il_light_desc l = {.type = spot ? IL_LIGHT_SPOT : IL_LIGHT_POINT, .position = q,
                       .intensity = v3s(I), .direction = v3(0, -1, 0), .spot_angle = 25.0f,
                       .spot_exponent = 3.0f};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);

    il_radiosity_desc rad = {.subdivisions = 3};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .threads = 2, .radiosity = &rad};
    rad_case c;
    memset(&c, 0, sizeof c);
    CHECK_OK(il_rad_settings_resolve(s, &rd, &c.set, &g_err), &g_err);
    CHECK_OK(il_patch_mesh_build(s, &(il_patch_sizing){c.set.patch_size, c.set.subdivisions}, &c.mesh, &g_err), &g_err);
    if (!c.mesh) {
        il_scene_release(s);
        return;
    }
    CHECK_OK(il_rad_solution_init(&c.sol, c.mesh->num_patches, &g_err), &g_err);
    CHECK_OK(il_rad_direct(s, c.mesh, &c.set, &c.sol, &g_err), &g_err);

    double cos_cut = cos(25.0 * PI_D / 180.0);
    uint32_t floor_patches = 0, below = 0, lit = 0;
    double worst = 0.0;
    for (uint32_t i = 0; i < c.mesh->num_patches; i++) {
        const il_patch *p = &c.mesh->patches[i];
        double e = PI_D * c.sol.direct[i].x / rho;
        CHECK(c.sol.direct[i].x == c.sol.direct[i].y && c.sol.direct[i].y == c.sol.direct[i].z);
        if (p->normal.y < 0.99f) {
            /* Walls and ceiling: lit or not, never negative or NaN. */
            CHECK(e >= 0.0 && isfinite(e));
            if (spot)
                CHECK(e == 0.0); /* the 25-degree cone reaches only the floor */
            continue;
        }
        CHECK(p->num_corners == 4);
        floor_patches++;
        double x0, x1, z0, z1;
        patch_bounds(c.mesh, p, &x0, &x1, &z0, &z1);
        double expect = floor_irradiance(x0, x1, z0, z1, q, I, spot ? 3.0 : -1.0, cos_cut);
        /* Patches cut by the cone's edge are partly lit: their estimate from
         * 16 points is coarse; the rest must match within 1%. */
        bool edge = false;
        if (spot) {
            double c00 = floor_irradiance(x0, x0, z0, z0, q, I, 3.0, cos_cut);
            double c11 = floor_irradiance(x1, x1, z1, z1, q, I, 3.0, cos_cut);
            double c01 = floor_irradiance(x0, x0, z1, z1, q, I, 3.0, cos_cut);
            double c10 = floor_irradiance(x1, x1, z0, z0, q, I, 3.0, cos_cut);
            int n_lit = (c00 > 0) + (c11 > 0) + (c01 > 0) + (c10 > 0);
            edge = n_lit > 0 && n_lit < 4;
        }
        if (expect > 0.0)
            lit++;
        if (!edge) {
            if (expect > 0.0)
                worst = fmax(worst, fabs(e - expect) / expect);
            else
                CHECK(e == 0.0);
        }
        if (x0 < q.x && q.x < x1 && z0 < q.z && q.z < z1) {
            below++;
            /* The patch right below: E = I / h^2 at its centre. */
            CHECK_REL(e, I / (q.y * q.y), 0.01);
        }
    }
    printf("%s light: %u floor patches, %u lit, worst %.3f%%\n", spot ? "spot" : "point",
           floor_patches, lit, 100.0 * worst);
    CHECK(floor_patches == 64);
    CHECK(below == 1);
    CHECK(worst < 0.01);
    if (spot)
        CHECK(lit > 4 && lit < 64);
    else
        CHECK(lit == 64);
    rad_case_free(&c);
    il_scene_release(s);
}

/* An open floor under a directional light and a sky: E cos + pi L on
 * every patch.  With a disc of diameter D the 16 points of a patch look
 * at 16 jittered directions across it, whose cosines spread +-5% at 6
 * degrees: their mean is E cos within 1%. */
static void test_directional_and_sky(float diameter, double tol)
{
    const float rho = 0.6f, El = 3.0f, Lsky = 0.25f;
    il_scene *s = new_scene();
    uint32_t grey = diffuse_material(s, v3s(rho), v3s(0));
    add_floor(s, 0.0f, 1.0f, grey); /* [-1,1]^2 at y = 0, facing up */
    il_vec3 dir = v3_normalize(v3(1.0f, -1.0f, 0.0f)); /* 45 degrees, travelling +x */
    il_light_desc l = {.type = IL_LIGHT_DIRECTIONAL, .direction = dir, .intensity = v3s(El),
                       .diameter = diameter};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    il_environment_desc env = {.radiance = v3s(Lsky)};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);

    il_radiosity_desc rad = {.subdivisions = 2};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .threads = 2, .radiosity = &rad};
    rad_case c;
    memset(&c, 0, sizeof c);
    CHECK_OK(il_rad_settings_resolve(s, &rd, &c.set, &g_err), &g_err);
    CHECK_OK(il_patch_mesh_build(s, &(il_patch_sizing){c.set.patch_size, c.set.subdivisions}, &c.mesh, &g_err), &g_err);
    if (c.mesh) {
        CHECK_OK(il_rad_solution_init(&c.sol, c.mesh->num_patches, &g_err), &g_err);
        CHECK_OK(il_rad_direct(s, c.mesh, &c.set, &c.sol, &g_err), &g_err);
        CHECK(c.mesh->num_patches == 16);
        double expect = El * cos(PI_D / 4.0) + PI_D * Lsky, worst = 0.0;
        for (uint32_t i = 0; i < c.mesh->num_patches; i++) {
            CHECK_REL(PI_D * c.sol.direct[i].y / rho, expect, tol);
            worst = fmax(worst, fabs(PI_D * c.sol.direct[i].y / rho / expect - 1.0));
        }
        printf("directional (disc %g deg) and sky: patches within %.2g of E cos + pi L\n", (double)diameter, worst);
    }
    rad_case_free(&c);
    il_scene_release(s);
}

/* A point light behind a wall: the patches on the far side get nothing. */
static void test_shadow(void)
{
    il_scene *s = new_scene();
    uint32_t grey = diffuse_material(s, v3s(0.5f), v3s(0));
    add_floor(s, 0.0f, 1.0f, grey);
    /* An occluding square at y = 0.25 facing up, covering x, z in [-0.5, 0.5]:
     * its shadow on the floor is [-2/3, 2/3]^2. */
    add_floor(s, 0.25f, 0.5f, grey);
    il_light_desc l = {.type = IL_LIGHT_POINT, .position = v3(0, 1.0f, 0), .intensity = v3s(1)};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    il_radiosity_desc rad = {.subdivisions = 3};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .threads = 1, .radiosity = &rad};
    rad_case c;
    memset(&c, 0, sizeof c);
    CHECK_OK(il_rad_settings_resolve(s, &rd, &c.set, &g_err), &g_err);
    CHECK_OK(il_patch_mesh_build(s, &(il_patch_sizing){c.set.patch_size, c.set.subdivisions}, &c.mesh, &g_err), &g_err);
    if (c.mesh) {
        CHECK_OK(il_rad_solution_init(&c.sol, c.mesh->num_patches, &g_err), &g_err);
        CHECK_OK(il_rad_direct(s, c.mesh, &c.set, &c.sol, &g_err), &g_err);
        uint32_t dark = 0, bright = 0, lit = 0;
        for (uint32_t i = 0; i < c.mesh->num_patches; i++) {
            const il_patch *p = &c.mesh->patches[i];
            if (p->center.y > 0.1f) {
                bright += c.sol.direct[i].x > 0.0f; /* the occluder's top */
                continue;
            }
            /* Floor patches (0.25 m) inside the shadow, and those outside it. */
            if (fabsf(p->center.x) < 0.5f && fabsf(p->center.z) < 0.5f) {
                CHECK(c.sol.direct[i].x == 0.0f);
                dark++;
            }
            if (fabsf(p->center.x) > 0.8f || fabsf(p->center.z) > 0.8f) {
                CHECK(c.sol.direct[i].x > 0.0f);
                lit++;
            }
        }
        CHECK(dark == 16);
        CHECK(lit == 28);
        CHECK(bright == 64);
    }
    rad_case_free(&c);
    il_scene_release(s);
}

int main(void)
{
    test_point_and_spot(false);
    test_point_and_spot(true);
    test_directional_and_sky(0.0f, 1e-5);
    test_directional_and_sky(6.0f, 1e-2);
    test_shadow();
    return check_report();
}
