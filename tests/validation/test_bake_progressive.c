/* il_bake_progressive on the Cornell box, radiosity (progressive shooting)
 * and hierarchical radiosity: the step callback sees meshes of the scene
 * (radiosity: laid out exactly as il_bake's), the first of them more than 2%
 * away from the final solution in mean luminance and the last within 2% of
 * it (the solve converges; radiosity's looks carry the ambient term), the
 * result equals il_bake's bit for bit, and a callback that returns false
 * at the first look stops the solve early with a result more than 1% away
 * from the full one.
 * Every baked triangle names its patch (il_bake_mesh.patches): as many
 * distinct patches as the solver reports, the triangles of one patch in
 * one plane. */
#include <string.h>

#include "check.h"
#include "illum/illum.h"

static il_error g_err;

typedef struct watch {
    uint32_t calls, stop_after;
    il_bake_result first;         /* a deep copy of the first look */
    bool same_layout;             /* every look has the first look's layout */
    double last;                  /* the last look's mean luminance */
} watch;

static double mean_luminance(const il_bake_result *b)
{
    double sum = 0.0;
    size_t n = 0;
    for (uint32_t m = 0; m < b->num_meshes; m++)
        for (uint32_t v = 0; v < b->meshes[m].num_vertices; v++, n++) {
            const float *L = b->meshes[m].radiance + 3 * (size_t)v;
            sum += 0.2126 * L[0] + 0.7152 * L[1] + 0.0722 * L[2];
        }
    return n ? sum / (double)n : 0.0;
}

static bool same_layout(const il_bake_result *a, const il_bake_result *b)
{
    if (a->num_meshes != b->num_meshes)
        return false;
    for (uint32_t m = 0; m < a->num_meshes; m++) {
        const il_bake_mesh *x = &a->meshes[m], *y = &b->meshes[m];
        if (x->num_vertices != y->num_vertices || x->num_triangles != y->num_triangles ||
            memcmp(x->positions, y->positions, 3 * sizeof(float) * x->num_vertices) ||
            memcmp(x->indices, y->indices, 3 * sizeof(uint32_t) * x->num_triangles))
            return false;
    }
    return true;
}

static bool same_radiance(const il_bake_result *a, const il_bake_result *b)
{
    if (!same_layout(a, b))
        return false;
    for (uint32_t m = 0; m < a->num_meshes; m++)
        if (memcmp(a->meshes[m].radiance, b->meshes[m].radiance,
                   3 * sizeof(float) * a->meshes[m].num_vertices))
            return false;
    return true;
}

static void copy_result(il_bake_result *dst, const il_bake_result *src)
{
    dst->num_meshes = src->num_meshes;
    dst->meshes = calloc(src->num_meshes, sizeof *dst->meshes);
    for (uint32_t m = 0; m < src->num_meshes; m++) {
        const il_bake_mesh *s = &src->meshes[m];
        il_bake_mesh *d = &dst->meshes[m];
        *d = *s;
        size_t nv = 3 * sizeof(float) * s->num_vertices + 1;
        size_t ni = 3 * sizeof(uint32_t) * s->num_triangles + 1;
        d->positions = memcpy(malloc(nv), s->positions, nv - 1);
        d->normals = memcpy(malloc(nv), s->normals, nv - 1);
        d->radiance = memcpy(malloc(nv), s->radiance, nv - 1);
        d->indices = memcpy(malloc(ni), s->indices, ni - 1);
    }
}

static double mean_luminance(const il_bake_result *b);

static bool on_step(const il_bake_result *cur, void *user)
{
    watch *w = user;
    w->last = mean_luminance(cur);
    if (w->calls++ == 0) {
        copy_result(&w->first, cur);
        w->same_layout = true;
    } else {
        w->same_layout = w->same_layout && same_layout(cur, &w->first);
    }
    return w->stop_after == 0 || w->calls < w->stop_after;
}

static void release_copy(il_bake_result *b)
{
    for (uint32_t m = 0; m < b->num_meshes; m++) {
        free(b->meshes[m].positions);
        free(b->meshes[m].normals);
        free(b->meshes[m].radiance);
        free(b->meshes[m].indices);
    }
    free(b->meshes);
    memset(b, 0, sizeof *b);
}

typedef struct vec3f {
    float x, y, z;
} vec3f;

static vec3f tri_normal(const il_bake_mesh *m, uint32_t t)
{
    const float *a = m->positions + 3 * (size_t)m->indices[3 * t],
                *b = m->positions + 3 * (size_t)m->indices[3 * t + 1],
                *c = m->positions + 3 * (size_t)m->indices[3 * t + 2];
    float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    vec3f n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    float len = sqrtf(n.x * n.x + n.y * n.y + n.z * n.z);
    return len > 0.0f ? (vec3f){n.x / len, n.y / len, n.z / len} : n;
}

/* The patch of every triangle: ids below `patches`, each id used, the
 * triangles of one patch in one plane (their normals agree). */
static void check_patches(const il_bake_result *b, uint64_t patches, const char *name)
{
    vec3f *normal = calloc(patches ? patches : 1, sizeof *normal);
    unsigned char *seen = calloc(patches ? patches : 1, 1);
    uint64_t distinct = 0, bad_id = 0, bent = 0;
    for (uint32_t m = 0; m < b->num_meshes; m++) {
        const il_bake_mesh *bm = &b->meshes[m];
        CHECK(bm->patches != NULL);
        if (!bm->patches)
            continue;
        for (uint32_t t = 0; t < bm->num_triangles; t++) {
            uint32_t p = bm->patches[t];
            if (p == UINT32_MAX)
                continue;
            if (p >= patches) {
                bad_id++;
                continue;
            }
            vec3f n = tri_normal(bm, t);
            if (!seen[p]) {
                seen[p] = 1;
                normal[p] = n;
                distinct++;
            } else if (n.x * normal[p].x + n.y * normal[p].y + n.z * normal[p].z < 0.999f) {
                bent++;
            }
        }
    }
    printf("%s: %llu patches named by the triangles of %llu, %llu ids out of range, %llu "
           "triangles off their patch's plane\n", name, (unsigned long long)distinct,
           (unsigned long long)patches, (unsigned long long)bad_id, (unsigned long long)bent);
    CHECK(patches > 0 && distinct == patches);
    CHECK(bad_id == 0);
    CHECK(bent == 0);
    free(normal);
    free(seen);
}

static void check_method(const il_scene *s, il_render_desc *rd, const char *name,
                         bool fixed_mesh)
{
    il_bake_result *plain = NULL, *prog = NULL, *stopped = NULL;
    CHECK_OK(il_bake(s, rd, &plain, &g_err), &g_err);
    watch w = {0};
    CHECK_OK(il_bake_progressive(s, rd, on_step, &w, &prog, &g_err), &g_err);
    if (!plain || !prog)
        return;
    double lf = mean_luminance(prog), l0 = w.calls ? mean_luminance(&w.first) : 0.0;
    printf("%s: %u looks, mean luminance first %.5f, last %.5f, result %.5f, il_bake %.5f\n",
           name, w.calls, l0, w.last, lf, mean_luminance(plain));
    CHECK(w.calls >= 2);
    CHECK(w.calls > 0 && w.first.num_meshes == prog->num_meshes);
    if (fixed_mesh) {  /* radiosity: the final mesh with an earlier radiance */
        CHECK(w.same_layout);
        CHECK(w.calls > 0 && same_layout(&w.first, prog));
    }
    CHECK(lf > 0.01);
    CHECK(fabs(l0 - lf) > 0.02 * lf);
    CHECK(fabs(w.last - lf) < 0.02 * lf);
    CHECK(same_radiance(prog, plain));
    release_copy(&w.first);
    check_patches(plain, fixed_mesh ? plain->stats.radiosity.num_patches : plain->stats.hr.leaves, name);

    /* Stopped after the first look: a valid result, away from the full one
     * (hr takes few looks: an iteration sweeps its links' system solved,
     * so its second look can be its last). */
    watch ws = {.stop_after = 1};
    CHECK_OK(il_bake_progressive(s, rd, on_step, &ws, &stopped, &g_err), &g_err);
    CHECK(ws.calls == 1);
    if (stopped) {
        double ls = mean_luminance(stopped);
        printf("%s: stopped after 1 look: mean luminance %.5f\n", name, ls);
        CHECK(ls > 0.0 && fabs(ls - lf) > 0.01 * lf);
    }
    release_copy(&ws.first);
    il_bake_release(plain);
    il_bake_release(prog);
    il_bake_release(stopped);
}

int main(void)
{
    il_scene *s = NULL;
    CHECK_OK(il_scene_load("cornell", NULL, &s, &g_err), &g_err);
    if (s)
        CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    if (!s)
        return check_report();

    il_radiosity_desc rad = {.subdivisions = 2};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .threads = 1, .seed = 3,
                         .radiosity = &rad};
    check_method(s, &rd, "radiosity", true);

    il_hr_desc hd = {0};
    il_render_desc hr = {.method = IL_METHOD_HR, .threads = 1, .seed = 3, .hr = &hd};
    check_method(s, &hr, "hr", false);

    /* Bad input as il_bake: a method that cannot bake. */
    il_render_desc pt = {.method = IL_METHOD_PT};
    il_bake_result *none = NULL;
    CHECK(il_bake_progressive(s, &pt, on_step, NULL, &none, &g_err) == IL_ERR_INVALID);
    CHECK(none == NULL);
    il_scene_release(s);
    return check_report();
}
