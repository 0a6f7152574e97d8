/* Energy balance of the hierarchical radiosity solution: the power emitted
 * equals the power absorbed plus (open scenes) the power that escapes,
 * within 1%.  In radiance units (power / pi), per leaf of area A:
 *   emitted   = A lum(Le)                        (the lamp's own emission)
 *   absorbed  = A lum((1 - rho) H)               H: the radiance arriving,
 *                                                sum of F V B over the links
 *                                                of the leaf and its ancestors
 *   escaped   = A lum(B) * (fraction of cosine-distributed rays from the leaf
 *               that leave the scene)            measured here independently,
 *                                                64 rays per leaf;
 *   backs     = A lum(B) * (fraction of those rays that hit the back of a
 *               surface: patches are one-sided, so light arriving at a back
 *               face (the lamp's, seen from the ceiling) is absorbed there
 *               and no link carries it).
 * At the fixed point B = Le + rho H the balance holds exactly only when the
 * links' form factors and visibilities keep reciprocity (A_r F_rs = A_s F_sr
 * summed over the scene), so it checks the link estimates and the push-pull
 * (area-weighted), not just arithmetic.  The block floats 0.1 m above the
 * floor: a block standing on it would hide floor that coarse elements
 * still light on average (a discretisation error, not a leak). */
#include "hr_scenes.h"
#include "core/rng.h"
#include "core/sampling.h"

typedef struct balance {
    const il_scene *scene;
    double emitted, absorbed, escaped, backs, leaving, arriving;
} balance;

static void add_leaf(const il_hr_elem *e, void *user)
{
    balance *b = user;
    const il_patch_mesh *unused = NULL;
    (void)unused;
    b->emitted += (double)e->area * il_luminance(e->emit);
    b->absorbed += (double)e->area * il_luminance(v3_mul(v3_sub(v3s(1.0f), e->rho), e->incoming));
    double lb = (double)e->area * il_luminance(e->radiance);
    b->leaving += lb;
    b->arriving += (double)e->area * il_luminance(e->incoming);
    if (lb <= 0.0)
        return;
    il_pcg32 rng = il_pcg32_seed(7, e->id);
    il_frame f = il_frame_from_normal(e->normal);
    int out = 0, back = 0;
    const int n = 64;
    for (int k = 0; k < n; k++) {
        float u = il_pcg32_float(&rng), v = il_pcg32_float(&rng);
        /* A uniform point on the element: its bilinear / barycentric map. */
        float a = il_pcg32_float(&rng), c = il_pcg32_float(&rng);
        il_vec3 p;
        if (e->num_corners == 4) {
            p = v3_add(v3_add(v3_scale(e->corners[0], (1 - a) * (1 - c)), v3_scale(e->corners[1], a * (1 - c))),
                       v3_add(v3_scale(e->corners[2], a * c), v3_scale(e->corners[3], (1 - a) * c)));
        } else {
            il_vec2 bc = il_sample_triangle(v2(a, c));
            p = v3_add(v3_add(v3_scale(e->corners[0], 1 - bc.x - bc.y), v3_scale(e->corners[1], bc.x)),
                       v3_scale(e->corners[2], bc.y));
        }
        il_vec3 d = il_frame_to_world(&f, il_sample_cosine_hemisphere(v2(u, v)));
        il_ray ray = {.org = il_offset_origin(b->scene->tracer, p, e->normal, d), .tmin = 0.0f,
                      .dir = d, .tmax = INFINITY};
        il_hit hit;
        if (!il_trace_closest(b->scene->tracer, &ray, &hit)) {
            out++;
            continue;
        }
        const il_mesh *m = &b->scene->meshes[hit.mesh];
        const uint32_t *t = m->indices + 3 * (size_t)hit.prim;
        il_vec3 ng = v3_cross(v3_sub(m->positions[t[1]], m->positions[t[0]]),
                              v3_sub(m->positions[t[2]], m->positions[t[0]]));
        back += v3_dot(ng, d) > 0.0f;
    }
    b->escaped += lb * out / n;
    b->backs += lb * back / n;
}

static void check_balance(bool open)
{
    il_scene *s = hr_room(open, true);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    /* The default epsilons (balance within 0.8% both ways). */
    il_hr_desc hd = {.energy_eps = 1e-6f};
    il_render_desc rd = {.method = IL_METHOD_HR, .threads = 2, .hr = &hd};
    hr_case c;
    CHECK_OK(hr_case_run(s, &rd, &c), &g_err);
    hr_print_stats(open ? "open room" : "closed room", &c.solver.stats);
    balance b = {.scene = s};
    for (uint32_t i = 0; i < c.solver.num_roots; i++)
        hr_visit_leaves(&c.solver.roots[i], add_leaf, &b);
    double sum = b.absorbed + b.backs + b.escaped;
    printf("leaving %.5f arriving %.5f\n", b.leaving, b.arriving);
    printf("emitted %.5f absorbed %.5f (+ %.5f by back faces) escaped %.5f: ratio %.4f\n",
           b.emitted, b.absorbed, b.backs, b.escaped, sum / b.emitted);
    CHECK(b.emitted > 0.0);
    CHECK_REL(sum, b.emitted, 0.01);
    if (open)
        CHECK(b.escaped > 0.1 * b.emitted); /* the open side lets much out */
    else
        CHECK(b.escaped == 0.0);
    hr_case_free(&c);
    il_scene_release(s);
}

int main(void)
{
    check_balance(false);
    check_balance(true);
    return check_report();
}
