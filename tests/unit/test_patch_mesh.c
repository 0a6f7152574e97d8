/* Radiosity meshing (rad_mesh*.c): surfaces, quads, uniform and patch-size
 * subdivision, welding only inside a surface, mirror triangles, refinement,
 * the BVH over the patch triangles, and the error paths. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "methods/radiosity/rad.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* ------------------------------------------------------------ scene helpers */

static il_vec3 sub3(il_vec3 a, il_vec3 b) { return v3_sub(a, b); }

/* Appends a triangle (a, b, c) to idx, turned so its winding normal points
 * along `front`. */
static void add_tri(uint32_t *idx, int *n, const il_vec3 *p, uint32_t a, uint32_t b, uint32_t c,
                    il_vec3 front)
{
    il_vec3 nw = v3_cross(sub3(p[b], p[a]), sub3(p[c], p[a]));
    if (v3_dot(nw, front) < 0.0f) {
        uint32_t t = b;
        b = c;
        c = t;
    }
    idx[(*n)++] = a;
    idx[(*n)++] = b;
    idx[(*n)++] = c;
}

/* One mesh: the quad q0 q1 q2 q3 (in order around it) as 2 triangles facing `front`. */
static void add_quad(il_scene *scene, const char *name, const il_vec3 q[4], il_vec3 front,
                     uint32_t material, const float *uvs)
{
    il_error err = {0};
    uint32_t idx[6];
    int n = 0;
    add_tri(idx, &n, q, 0, 1, 2, front);
    add_tri(idx, &n, q, 0, 2, 3, front);
    CHECK_OK(il_scene_add_mesh(scene, &(il_mesh_desc){.name = name, .num_vertices = 4,
                                                       .num_triangles = 2, .positions = &q[0].x,
                                                       .uvs = uvs, .indices = idx,
                                                       .material = material},
                               &err),
             &err);
}

static il_vec3 corner(int i, float s) { return v3((i & 1) ? s : 0, (i & 2) ? s : 0, (i & 4) ? s : 0); }

/* The 6 faces of the cube [0,s]^3 as corner indices in order around the
 * face, and each face's inward normal. */
static const int face_corners[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                       {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
static const float face_in[6][3] = {{0, 0, 1}, {0, 0, -1}, {0, 1, 0},
                                    {0, -1, 0}, {1, 0, 0}, {-1, 0, 0}};

/* A closed box of side s facing inwards: 6 meshes of 2 triangles (one
 * material each, the ceiling y = s emissive), or one mesh of 8 shared
 * vertices and 12 triangles with a point light. */
static il_scene *make_box(float s, bool one_mesh)
{
    il_error err = {0};
    il_scene *scene = NULL;
    CHECK_OK(il_scene_create(&scene, &err), &err);
    il_vec3 c[8];
    for (int i = 0; i < 8; i++)
        c[i] = corner(i, s);
    if (one_mesh) {
        uint32_t grey;
        CHECK_OK(il_scene_add_material(scene, &(il_material_desc){.diffuse = {0.5f, 0.5f, 0.5f}},
                                       &grey, &err),
                 &err);
        uint32_t idx[36];
        int n = 0;
        for (int f = 0; f < 6; f++) {
            const int *q = face_corners[f];
            il_vec3 in = v3(face_in[f][0], face_in[f][1], face_in[f][2]);
            add_tri(idx, &n, c, (uint32_t)q[0], (uint32_t)q[1], (uint32_t)q[2], in);
            add_tri(idx, &n, c, (uint32_t)q[0], (uint32_t)q[2], (uint32_t)q[3], in);
        }
        CHECK_OK(il_scene_add_mesh(scene, &(il_mesh_desc){.name = "box", .num_vertices = 8,
                                                           .num_triangles = 12, .positions = &c[0].x,
                                                           .indices = idx, .material = grey},
                                   &err),
                 &err);
        CHECK_OK(il_scene_add_light(scene, &(il_light_desc){.type = IL_LIGHT_POINT,
                                                            .position = {s / 2, s / 2, s / 2},
                                                            .intensity = {1, 1, 1}},
                                    &err),
                 &err);
    } else {
        for (int f = 0; f < 6; f++) {
            uint32_t mat;
            il_material_desc md = {.diffuse = {0.1f * (float)f, 0.5f, 0.5f}};
            if (f == 3)
                md.emission = v3(2, 3, 4);
            CHECK_OK(il_scene_add_material(scene, &md, &mat, &err), &err);
            il_vec3 q[4];
            for (int k = 0; k < 4; k++)
                q[k] = c[face_corners[f][k]];
            char name[16];
            snprintf(name, sizeof name, "wall%d", f);
            add_quad(scene, name, q, v3(face_in[f][0], face_in[f][1], face_in[f][2]), mat, NULL);
        }
    }
    CHECK_OK(il_scene_commit(scene, &err), &err);
    return scene;
}

static il_patch_sizing settings_of(float patch_size, uint32_t subdivisions)
{
    return (il_patch_sizing){.patch_size = patch_size, .subdivisions = subdivisions};
}

/* ------------------------------------------------------------ mesh checks */

static double total_area(const il_patch_mesh *m)
{
    double a = 0.0;
    for (uint32_t i = 0; i < m->num_patches; i++)
        a += m->patches[i].area;
    return a;
}

typedef struct vkey { uint32_t surface; float x, y, z; } vkey;

static int cmp_vkey(const void *a, const void *b)
{
    const vkey *p = a, *q = b;
    if (p->surface != q->surface)
        return p->surface < q->surface ? -1 : 1;
    if (p->x != q->x)
        return p->x < q->x ? -1 : 1;
    if (p->y != q->y)
        return p->y < q->y ? -1 : 1;
    if (p->z != q->z)
        return p->z < q->z ? -1 : 1;
    return 0;
}

/* Invariants every mesh must satisfy: corners of one surface, counter-
 * clockwise around the normal, positive areas, consistent triangles, no two
 * vertices of one surface at one position. */
static void check_invariants(const il_patch_mesh *m)
{
    uint32_t bad_surface = 0, bad_winding = 0, bad_area = 0, bad_normal = 0;
    for (uint32_t i = 0; i < m->num_patches; i++) {
        const il_patch *p = &m->patches[i];
        for (uint32_t k = 0; k < p->num_corners; k++)
            bad_surface += m->vertex_surface[p->v[k]] != p->surface;
        for (uint32_t k = 0; k < p->num_corners; k++) {
            il_vec3 a = m->positions[p->v[k]], b = m->positions[p->v[(k + 1) % p->num_corners]],
                    c = m->positions[p->v[(k + 2) % p->num_corners]];
            bad_winding += v3_dot(v3_cross(sub3(b, a), sub3(c, b)), p->normal) <= 0.0f;
        }
        bad_area += !(p->area > 0.0f);
        bad_normal += fabsf(v3_length(p->normal) - 1.0f) > 1e-5f;
        CHECK(m->surfaces[p->surface].diffuse);
    }
    CHECK(bad_surface == 0);
    CHECK(bad_winding == 0);
    CHECK(bad_area == 0);
    CHECK(bad_normal == 0);

    /* Triangles: each patch's 1 or 2, pointing at it. */
    uint32_t *count = calloc(m->num_patches + 1, sizeof *count);
    for (uint32_t t = 0; t < m->num_tris; t++) {
        CHECK(m->tri_indices[3 * t] < m->num_vertices && m->tri_indices[3 * t + 1] < m->num_vertices &&
              m->tri_indices[3 * t + 2] < m->num_vertices);
        if (m->tri_patch[t] != IL_NO_PATCH)
            count[m->tri_patch[t]]++;
    }
    uint32_t bad_count = 0;
    for (uint32_t i = 0; i < m->num_patches; i++)
        bad_count += count[i] != m->patches[i].num_corners - 2;
    CHECK(bad_count == 0);
    free(count);

    vkey *keys = malloc((m->num_vertices + 1) * sizeof *keys);
    for (uint32_t v = 0; v < m->num_vertices; v++)
        keys[v] = (vkey){m->vertex_surface[v], m->positions[v].x, m->positions[v].y, m->positions[v].z};
    qsort(keys, m->num_vertices, sizeof *keys, cmp_vkey);
    uint32_t dup = 0;
    for (uint32_t v = 1; v < m->num_vertices; v++)
        dup += cmp_vkey(&keys[v - 1], &keys[v]) == 0;
    CHECK(dup == 0);
    free(keys);
}

static uint32_t vertices_of_surface(const il_patch_mesh *m, uint32_t s)
{
    uint32_t n = 0;
    for (uint32_t v = 0; v < m->num_vertices; v++)
        n += m->vertex_surface[v] == s;
    return n;
}

/* ------------------------------------------------------------------ tests */

static void test_box_levels(void)
{
    il_error err = {0};
    il_scene *scene = make_box(2.0f, false);
    const uint32_t levels[3] = {0, 5, 6}, expect[3] = {6, 6144, 24576};
    for (int l = 0; l < 3; l++) {
        il_patch_sizing s = settings_of(100.0f, levels[l]);
        il_patch_mesh *m = NULL;
        CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
        if (!m)
            continue;
        CHECK(m->num_patches == expect[l]);
        CHECK(m->num_surfaces == 6);
        CHECK(m->num_tris == 2 * expect[l]);
        CHECK_REL(total_area(m), 6.0 * 4.0, 1e-5);
        check_invariants(m);
        uint32_t side = (1u << levels[l]) + 1;
        for (uint32_t f = 0; f < 6; f++)
            CHECK(vertices_of_surface(m, f) == side * side);
        CHECK(m->num_vertices == 6 * side * side);
        uint32_t quads = 0, inward = 0, lit = 0;
        for (uint32_t i = 0; i < m->num_patches; i++) {
            const il_patch *p = &m->patches[i];
            quads += p->num_corners == 4;
            il_vec3 to_centre = v3_sub(v3(1, 1, 1), p->center);
            inward += v3_dot(p->normal, to_centre) > 0.0f;
            const il_patch_surface *su = &m->surfaces[p->surface];
            il_vec3 kd = scene->materials[su->material].diffuse;
            CHECK_NEAR(p->rho.x, kd.x, 1e-6);
            if (!v3_is_zero(p->emission)) {
                lit++;
                CHECK(su->mesh == 3);
                CHECK_NEAR(p->emission.z, 4.0, 0.0);
                CHECK_NEAR(p->normal.y, -1.0, 1e-6);
            }
        }
        CHECK(quads == m->num_patches);
        CHECK(inward == m->num_patches);
        CHECK(lit == expect[l] / 6);
        if (levels[l] == 0) {
            /* One quad per wall, exactly the wall's corners. */
            for (uint32_t i = 0; i < 6; i++) {
                CHECK_NEAR(m->patches[i].area, 4.0, 1e-5);
                CHECK(m->patches[i].surface == i);
                CHECK(m->surfaces[i].mesh == i);
            }
        }
        il_patch_mesh_release(m);
    }
    il_scene_release(scene);
}

/* One mesh with shared corners: split at the 90-degree creases into 6
 * surfaces that share no vertex. */
static void test_box_one_mesh(void)
{
    il_error err = {0};
    il_scene *scene = make_box(1.0f, true);
    for (uint32_t level = 0; level <= 2; level++) {
        il_patch_sizing s = settings_of(100.0f, level);
        il_patch_mesh *m = NULL;
        CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
        if (!m)
            continue;
        uint32_t n = 1u << level;
        CHECK(m->num_surfaces == 6);
        CHECK(m->num_patches == 6 * n * n);
        CHECK(m->num_vertices == 6 * (n + 1) * (n + 1));
        CHECK_REL(total_area(m), 6.0, 1e-5);
        check_invariants(m);
        uint32_t quads = 0;
        for (uint32_t i = 0; i < m->num_patches; i++)
            quads += m->patches[i].num_corners == 4;
        CHECK(quads == m->num_patches);
        il_patch_mesh_release(m);
    }
    il_scene_release(scene);
}

/* One quad of w x h in the plane z = 0 facing +z, and a point light. */
static il_scene *make_quad(float w, float h, const float *uvs, uint32_t texture,
                           il_material_type type)
{
    il_error err = {0};
    il_scene *scene = NULL;
    CHECK_OK(il_scene_create(&scene, &err), &err);
    uint32_t mat;
    CHECK_OK(il_scene_add_material(scene, &(il_material_desc){.type = type,
                                                              .diffuse = {0.6f, 0.4f, 0.2f},
                                                              .specular = {0.1f, 0.1f, 0.1f},
                                                              .diffuse_texture = texture},
                                   &mat, &err),
             &err);
    il_vec3 q[4] = {{0, 0, 0}, {w, 0, 0}, {w, h, 0}, {0, h, 0}};
    add_quad(scene, "quad", q, v3(0, 0, 1), mat, uvs);
    CHECK_OK(il_scene_add_light(scene, &(il_light_desc){.type = IL_LIGHT_POINT, .position = {0, 0, 1},
                                                        .intensity = {1, 1, 1}},
                                &err),
             &err);
    return scene;
}

static void test_patch_size(void)
{
    il_error err = {0};
    il_scene *scene = make_quad(1.0f, 1.0f, NULL, 0, IL_MATERIAL_DIFFUSE);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    const float sizes[3] = {0.25f, 0.3f, 2.0f};
    const uint32_t expect[3] = {16, 16, 1};
    for (int k = 0; k < 3; k++) {
        il_patch_sizing s = settings_of(sizes[k], 0);
        il_patch_mesh *m = NULL;
        CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
        if (!m)
            continue;
        CHECK(m->num_patches == expect[k]);
        CHECK_REL(total_area(m), 1.0, 1e-5);
        check_invariants(m);
        for (uint32_t i = 0; i < m->num_patches; i++) {
            CHECK_NEAR(m->patches[i].normal.z, 1.0, 1e-6);
            CHECK_NEAR(m->patches[i].area, 1.0 / expect[k], 1e-6);
            CHECK_NEAR(m->patches[i].rho.y, 0.4, 1e-6);
        }
        il_patch_mesh_release(m);
    }
    il_scene_release(scene);

    /* 2 x 1 m at 0.5 m: 4 x 2 cells of 0.25 m^2. */
    scene = make_quad(2.0f, 1.0f, NULL, 0, IL_MATERIAL_PHONG);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    il_patch_sizing s = settings_of(0.5f, 0);
    il_patch_mesh *m = NULL;
    CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
    if (m) {
        CHECK(m->num_patches == 8);
        CHECK(m->num_vertices == 15);
        CHECK_REL(total_area(m), 2.0, 1e-6);
        CHECK_NEAR(m->patches[0].area, 0.25, 1e-6);
        CHECK(m->surfaces[0].diffuse);
        CHECK_NEAR(m->patches[0].rho.x, 0.6, 1e-6); /* Phong: its diffuse albedo */
        check_invariants(m);
        il_patch_mesh_release(m);
    }
    il_scene_release(scene);
}

/* A constant texture of 0.5 halves the albedo. */
static void test_texture(void)
{
    il_error err = {0};
    il_scene *scene = NULL;
    const float half[3 * 4] = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    const float uvs[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    uint32_t tex;
    CHECK_OK(il_scene_create(&scene, &err), &err);
    CHECK_OK(il_scene_add_texture(scene, 2, 2, half, &tex, &err), &err);
    uint32_t mat;
    CHECK_OK(il_scene_add_material(scene, &(il_material_desc){.diffuse = {0.6f, 0.4f, 0.2f},
                                                              .diffuse_texture = tex},
                                   &mat, &err),
             &err);
    il_vec3 q[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    add_quad(scene, "quad", q, v3(0, 0, 1), mat, uvs);
    CHECK_OK(il_scene_add_light(scene, &(il_light_desc){.type = IL_LIGHT_POINT, .position = {0, 0, 1},
                                                        .intensity = {1, 1, 1}},
                                &err),
             &err);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    il_patch_sizing s = settings_of(0.5f, 0);
    il_patch_mesh *m = NULL;
    CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
    if (m) {
        CHECK(m->num_patches == 4);
        for (uint32_t i = 0; i < m->num_patches; i++) {
            CHECK_NEAR(m->patches[i].rho.x, 0.3, 1e-6);
            CHECK_NEAR(m->patches[i].rho.z, 0.1, 1e-6);
        }
        il_patch_mesh_release(m);
    }
    il_scene_release(scene);
}

static void test_triangle_surface(void)
{
    il_error err = {0};
    il_scene *scene = NULL;
    CHECK_OK(il_scene_create(&scene, &err), &err);
    const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t idx[3] = {0, 1, 2};
    CHECK_OK(il_scene_add_mesh(scene, &(il_mesh_desc){.num_vertices = 3, .num_triangles = 1,
                                                       .positions = p, .indices = idx},
                               &err),
             &err);
    CHECK_OK(il_scene_add_light(scene, &(il_light_desc){.type = IL_LIGHT_POINT, .position = {0, 0, 1},
                                                        .intensity = {1, 1, 1}},
                                &err),
             &err);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    /* Level 2: 16 triangles, 15 vertices; patch size 0.5 on a longest edge
     * of sqrt(2): n = 3, 9 triangles, 10 vertices. */
    const il_patch_sizing set[2] = {settings_of(1.0f, 2), settings_of(0.5f, 0)};
    const uint32_t np[2] = {16, 9}, nv[2] = {15, 10};
    for (int k = 0; k < 2; k++) {
        il_patch_mesh *m = NULL;
        CHECK_OK(il_patch_mesh_build(scene, &set[k], &m, &err), &err);
        if (!m)
            continue;
        CHECK(m->num_patches == np[k]);
        CHECK(m->num_vertices == nv[k]);
        CHECK(m->num_surfaces == 1);
        CHECK_REL(total_area(m), 0.5, 1e-6);
        for (uint32_t i = 0; i < m->num_patches; i++) {
            CHECK(m->patches[i].num_corners == 3);
            CHECK_NEAR(m->patches[i].area, 0.5 / np[k], 1e-7);
            CHECK_NEAR(m->patches[i].normal.z, 1.0, 1e-6);
            CHECK_NEAR(m->patches[i].rho.x, 0.8, 1e-6); /* the default material */
        }
        check_invariants(m);
        il_patch_mesh_release(m);
    }
    il_scene_release(scene);
}

/* A box with a mirror quad inside: no patches for the mirror, its triangles
 * copied with the scene's vertex order. */
static void test_mirror(void)
{
    il_error err = {0};
    il_scene *scene = NULL;
    CHECK_OK(il_scene_create(&scene, &err), &err);
    uint32_t mirror, lamp;
    CHECK_OK(il_scene_add_material(scene, &(il_material_desc){.type = IL_MATERIAL_MIRROR}, &mirror, &err),
             &err);
    CHECK_OK(il_scene_add_material(scene, &(il_material_desc){.emission = {1, 1, 1}}, &lamp, &err), &err);
    il_vec3 floor[4] = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
    il_vec3 mq[4] = {{0.2f, 0.5f, 0.2f}, {0.8f, 0.5f, 0.2f}, {0.8f, 0.5f, 0.8f}, {0.2f, 0.5f, 0.8f}};
    il_vec3 lq[4] = {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}};
    add_quad(scene, "floor", floor, v3(0, 1, 0), 0, NULL);
    add_quad(scene, "mirror", mq, v3(0, 1, 0), mirror, NULL);
    add_quad(scene, "lamp", lq, v3(0, -1, 0), lamp, NULL);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    il_patch_sizing s = settings_of(0.5f, 0);
    il_patch_mesh *m = NULL;
    CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
    if (m) {
        CHECK(m->num_patches == 8);
        CHECK(m->num_surfaces == 3);
        CHECK(m->num_tris == 2 * 8 + 2);
        check_invariants(m);
        uint32_t raw = 0;
        for (uint32_t t = 0; t < m->num_tris; t++) {
            if (m->tri_patch[t] != IL_NO_PATCH)
                continue;
            raw++;
            CHECK(m->tri_src_mesh[t] == 1);
            const il_mesh *sm = &scene->meshes[1];
            for (int k = 0; k < 3; k++) {
                il_vec3 a = m->positions[m->tri_indices[3 * t + k]];
                il_vec3 b = sm->positions[sm->indices[3 * m->tri_src_prim[t] + k]];
                CHECK(a.x == b.x && a.y == b.y && a.z == b.z);
                CHECK(!m->surfaces[m->vertex_surface[m->tri_indices[3 * t + k]]].diffuse);
            }
        }
        CHECK(raw == 2);
        CHECK(!m->surfaces[1].diffuse && m->surfaces[1].mesh == 1);
        /* A ray down onto the mirror hits it (it occludes in the BVH). */
        il_hit hit;
        il_ray ray = {.org = {0.5f, 0.9f, 0.5f}, .dir = {0, -1, 0}, .tmax = 10.0f};
        CHECK(il_trace_closest(m->tracer, &ray, &hit));
        CHECK(hit.prim < m->num_tris && m->tri_patch[hit.prim] == IL_NO_PATCH);
        CHECK_NEAR(hit.t, 0.4, 1e-5);
        il_patch_mesh_release(m);
    }
    il_scene_release(scene);

    /* Only mirrors: nothing to mesh. */
    CHECK_OK(il_scene_create(&scene, &err), &err);
    CHECK_OK(il_scene_add_material(scene, &(il_material_desc){.type = IL_MATERIAL_DIELECTRIC}, &mirror, &err),
             &err);
    add_quad(scene, "glass", mq, v3(0, 1, 0), mirror, NULL);
    CHECK_OK(il_scene_add_light(scene, &(il_light_desc){.type = IL_LIGHT_POINT, .position = {0, 1, 0},
                                                        .intensity = {1, 1, 1}},
                                &err),
             &err);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    m = (il_patch_mesh *)1;
    CHECK(il_patch_mesh_build(scene, &s, &m, &err) == IL_ERR_INVALID);
    CHECK(m == NULL);
    CHECK(strstr(err.message, "no diffuse surface") != NULL);
    il_scene_release(scene);
}

/* Builds a one-mesh scene from raw arrays plus a point light, meshes it at
 * a large patch size; the caller releases both. */
static il_patch_mesh *mesh_of(const float *pos, uint32_t nv, const uint32_t *idx, uint32_t nt,
                            const float *normals, il_scene **scene_out)
{
    il_error err = {0};
    il_scene *scene = NULL;
    CHECK_OK(il_scene_create(&scene, &err), &err);
    CHECK_OK(il_scene_add_mesh(scene, &(il_mesh_desc){.num_vertices = nv, .num_triangles = nt,
                                                       .positions = pos, .normals = normals,
                                                       .indices = idx},
                               &err),
             &err);
    CHECK_OK(il_scene_add_light(scene, &(il_light_desc){.type = IL_LIGHT_POINT, .position = {0, 0, 5},
                                                        .intensity = {1, 1, 1}},
                                &err),
             &err);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    il_patch_sizing s = settings_of(100.0f, 0);
    il_patch_mesh *m = NULL;
    CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
    *scene_out = scene;
    return m;
}

/* Creases, repeated triangles, two-sided walls, the vertex normals' front. */
static void test_surfaces(void)
{
    il_scene *scene;
    il_patch_mesh *m;
    /* Two unit squares folded along x = 1 by 20 degrees (one surface, the
     * fold's 2 vertices shared) or by 40 degrees (two surfaces). */
    for (int k = 0; k < 2; k++) {
        float a = (k == 0 ? 20.0f : 40.0f) * IL_PI / 180.0f;
        float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                       1 + cosf(a), 0, sinf(a), 1 + cosf(a), 1, sinf(a)};
        const uint32_t idx[] = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2};
        m = mesh_of(pos, 6, idx, 4, NULL, &scene);
        if (m) {
            CHECK(m->num_surfaces == (k == 0 ? 1u : 2u));
            CHECK(m->num_patches == 2);
            CHECK(m->num_vertices == (k == 0 ? 6u : 8u));
            CHECK(m->patches[0].num_corners == 4 && m->patches[1].num_corners == 4);
            CHECK_REL(total_area(m), 2.0, 1e-5);
            check_invariants(m);
            il_patch_mesh_release(m);
        }
        il_scene_release(scene);
    }
    /* The unit square given twice, then once more facing the other way: the
     * repeat is dropped; the back face is its own surface. */
    {
        const float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
        const uint32_t idx[] = {0, 1, 2, 0, 2, 3, 2, 0, 1, 3, 0, 2, 0, 2, 1, 0, 3, 2};
        m = mesh_of(pos, 4, idx, 6, NULL, &scene);
        if (m) {
            CHECK(m->num_surfaces == 2);
            CHECK(m->num_patches == 2);
            CHECK(m->num_vertices == 8);
            CHECK_NEAR(m->patches[0].normal.z, 1.0, 1e-6);
            CHECK_NEAR(m->patches[1].normal.z, -1.0, 1e-6);
            CHECK_REL(total_area(m), 2.0, 1e-5);
            check_invariants(m);
            il_patch_mesh_release(m);
        }
        il_scene_release(scene);
    }
    /* Wound facing +z, vertex normals -z: the front is -z. */
    {
        const float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
        const float nrm[] = {0, 0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1};
        const uint32_t idx[] = {0, 1, 2, 0, 2, 3};
        m = mesh_of(pos, 4, idx, 2, nrm, &scene);
        if (m) {
            CHECK(m->num_patches == 1);
            CHECK_NEAR(m->patches[0].normal.z, -1.0, 1e-6);
            check_invariants(m);
            il_patch_mesh_release(m);
        }
        il_scene_release(scene);
    }
}

static void test_refine(void)
{
    il_error err = {0};
    il_scene *scene = make_box(1.0f, false);
    il_patch_sizing s = settings_of(100.0f, 1);
    il_patch_mesh *m = NULL, *r = NULL, *r2 = NULL;
    CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
    if (!m) {
        il_scene_release(scene);
        return;
    }
    CHECK(m->num_patches == 24);
    bool *split = calloc(m->num_patches, sizeof *split);
    split[0] = true;
    CHECK_OK(il_patch_mesh_refine(scene, m, split, &r, &err), &err);
    if (r) {
        CHECK(r->num_patches == 27);
        CHECK(r->num_surfaces == 6);
        CHECK(r->num_vertices == m->num_vertices + 5);
        CHECK_REL(total_area(r), 6.0, 1e-5);
        check_invariants(r);
        /* In place: 4 children first, then the old patches 1.. unchanged. */
        double kids = 0.0;
        for (int k = 0; k < 4; k++) {
            CHECK(r->patches[k].surface == m->patches[0].surface);
            CHECK_NEAR(r->patches[k].area, m->patches[0].area / 4, 1e-6);
            kids += r->patches[k].area;
        }
        CHECK_REL(kids, m->patches[0].area, 1e-6);
        for (uint32_t i = 1; i < m->num_patches; i++)
            CHECK(memcmp(&r->patches[i + 3], &m->patches[i], sizeof m->patches[i]) == 0);
        for (uint32_t v = 0; v < m->num_vertices; v++)
            CHECK(memcmp(&r->positions[v], &m->positions[v], sizeof(il_vec3)) == 0);

        /* Splitting two neighbours of one surface at once shares the
         * midpoint of their common edge: 5 + 5 - 1 new vertices (old
         * patches 4 and 5, cells (0,0) and (1,0) of wall 1, now 7 and 8);
         * old patch 1 (now 4) reuses the T-junction vertex its split
         * neighbour 0 left on their common edge: 4 new. */
        bool *split2 = calloc(r->num_patches, sizeof *split2);
        split2[7] = split2[8] = true;
        CHECK(r->patches[7].surface == r->patches[8].surface);
        CHECK_OK(il_patch_mesh_refine(scene, r, split2, &r2, &err), &err);
        if (r2) {
            CHECK(r2->num_patches == 27 + 6);
            CHECK(r2->num_vertices == r->num_vertices + 9);
            CHECK_REL(total_area(r2), 6.0, 1e-5);
            check_invariants(r2);
            il_patch_mesh_release(r2);
        }
        memset(split2, 0, r->num_patches * sizeof *split2);
        split2[4] = true;
        CHECK_OK(il_patch_mesh_refine(scene, r, split2, &r2, &err), &err);
        if (r2) {
            CHECK(r2->num_patches == 27 + 3);
            CHECK(r2->num_vertices == r->num_vertices + 4);
            check_invariants(r2);
            il_patch_mesh_release(r2);
        }
        free(split2);
        il_patch_mesh_release(r);
    }
    free(split);
    il_patch_mesh_release(m);

    /* Triangles split into 4 as well. */
    il_scene_release(scene);
    CHECK_OK(il_scene_create(&scene, &err), &err);
    const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t idx[3] = {0, 1, 2};
    CHECK_OK(il_scene_add_mesh(scene, &(il_mesh_desc){.num_vertices = 3, .num_triangles = 1,
                                                       .positions = p, .indices = idx},
                               &err),
             &err);
    CHECK_OK(il_scene_add_light(scene, &(il_light_desc){.type = IL_LIGHT_POINT, .position = {0, 0, 1},
                                                        .intensity = {1, 1, 1}},
                                &err),
             &err);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    s = settings_of(10.0f, 0);
    CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
    if (m) {
        bool one = true;
        CHECK(m->num_patches == 1);
        CHECK_OK(il_patch_mesh_refine(scene, m, &one, &r, &err), &err);
        if (r) {
            CHECK(r->num_patches == 4);
            CHECK(r->num_vertices == 6);
            CHECK_REL(total_area(r), 0.5, 1e-6);
            check_invariants(r);
            il_patch_mesh_release(r);
        }
        il_patch_mesh_release(m);
    }
    il_scene_release(scene);
}

static void test_errors(void)
{
    il_error err = {0};
    il_scene *scene = make_box(1.0f, false);
    il_patch_mesh *m = NULL;
    il_patch_sizing s = settings_of(1e-4f, 0);
    CHECK(il_patch_mesh_build(scene, &s, &m, &err) == IL_ERR_INVALID);
    CHECK(m == NULL);
    CHECK(strstr(err.message, "more than 4,000,000") != NULL);
    s = settings_of(1e-3f, 0); /* 6 walls of 1000^2 cells */
    CHECK(il_patch_mesh_build(scene, &s, &m, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "gives 6000000 patches") != NULL);
    s = settings_of(1.0f, 12); /* 6 * 4^12 */
    CHECK(il_patch_mesh_build(scene, &s, &m, &err) == IL_ERR_INVALID);
    s = settings_of(1.0f, 4000000000u);
    CHECK(il_patch_mesh_build(scene, &s, &m, &err) == IL_ERR_INVALID);
    const float bad[3] = {0.0f, -1.0f, NAN};
    for (int k = 0; k < 3; k++) {
        s = settings_of(bad[k], 0);
        CHECK(il_patch_mesh_build(scene, &s, &m, &err) == IL_ERR_INVALID);
        CHECK(m == NULL);
    }
    il_scene_release(scene);
}

/* Rays from the box's centre hit the patches of the wall they point at. */
static void test_tracer(void)
{
    il_error err = {0};
    il_scene *scene = make_box(1.0f, false);
    il_patch_sizing s = settings_of(0.1f, 0);
    il_patch_mesh *m = NULL;
    CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
    if (m) {
        CHECK(m->num_patches == 600);
        for (int f = 0; f < 6; f++) {
            il_vec3 in = v3(face_in[f][0], face_in[f][1], face_in[f][2]);
            il_vec3 dir = v3_add(v3_neg(in), v3(0.13f, 0.21f, 0.07f));
            il_ray ray = {.org = {0.5f, 0.5f, 0.5f}, .dir = dir, .tmax = 10.0f};
            il_hit hit;
            CHECK(il_trace_closest(m->tracer, &ray, &hit));
            uint32_t pi = m->tri_patch[hit.prim];
            CHECK(pi < m->num_patches);
            if (pi >= m->num_patches)
                continue;
            const il_patch *p = &m->patches[pi];
            CHECK(m->surfaces[p->surface].mesh == (uint32_t)f);
            CHECK(m->tri_src_mesh[hit.prim] == (uint32_t)f);
            il_vec3 x = v3_fma(ray.org, dir, hit.t);
            /* The hit lies within the patch: its cell is 0.1 m wide. */
            CHECK(v3_length(v3_sub(x, p->center)) < 0.0708f);
            CHECK(v3_dot(p->normal, in) > 0.999f);
        }
        il_patch_mesh_release(m);
    }
    il_scene_release(scene);
}

static bool same_point(il_vec3 a, il_vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

/* Whether triangle k of sm repeats an earlier one (the same 3 points, the
 * same facing): the mesher meshes it once.  Quadratic: small scenes only. */
static bool repeated(const il_mesh *sm, uint32_t k)
{
    const uint32_t *a = sm->indices + 3 * k;
    il_vec3 pa[3] = {sm->positions[a[0]], sm->positions[a[1]], sm->positions[a[2]]};
    il_vec3 na = v3_cross(sub3(pa[1], pa[0]), sub3(pa[2], pa[0]));
    for (uint32_t j = 0; j < k; j++) {
        const uint32_t *b = sm->indices + 3 * j;
        il_vec3 pb[3] = {sm->positions[b[0]], sm->positions[b[1]], sm->positions[b[2]]};
        int found = 0;
        for (int x = 0; x < 3; x++)
            for (int y = 0; y < 3; y++)
                if (same_point(pa[x], pb[y])) {
                    found++;
                    break;
                }
        il_vec3 nb = v3_cross(sub3(pb[1], pb[0]), sub3(pb[2], pb[0]));
        if (found == 3 && v3_dot(na, nb) > 0.0f)
            return true;
    }
    return false;
}

/* Sum of the areas of the scene's diffuse triangles, repeats counted once. */
static double diffuse_area(const il_scene *scene)
{
    double a = 0.0;
    for (uint32_t i = 0; i < scene->num_meshes; i++) {
        const il_mesh *sm = &scene->meshes[i];
        il_material_type t = scene->materials[sm->material].type;
        if (t == IL_MATERIAL_MIRROR || t == IL_MATERIAL_DIELECTRIC)
            continue;
        for (uint32_t k = 0; k < sm->num_triangles; k++) {
            if (repeated(sm, k))
                continue;
            const uint32_t *ix = sm->indices + 3 * k;
            il_vec3 p0 = sm->positions[ix[0]];
            a += 0.5 * v3_length(v3_cross(sub3(sm->positions[ix[1]], p0), sub3(sm->positions[ix[2]], p0)));
        }
    }
    return a;
}

/* A Cornell box meshed coarsely (one patch per face: 16 surfaces, 17
 * patches, 15 of them quads, the one wall out of plane as 2 triangles) and
 * finely (patch edges at most `fine` metres: more than min_fine patches);
 * both keep the diffuse area. */
static void check_cornell_meshing(const il_scene *scene, float fine, uint32_t min_fine,
                                  bool coarse_invariants)
{
    il_error err = {0};
    il_patch_sizing s = settings_of(100.0f, 0);
    il_patch_mesh *m = NULL;
    CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
    if (m) {
        CHECK(m->num_surfaces == 16);
        CHECK(m->num_patches == 17);
        uint32_t quads = 0;
        for (uint32_t i = 0; i < m->num_patches; i++)
            quads += m->patches[i].num_corners == 4;
        CHECK(quads == 15);
        CHECK_REL(total_area(m), diffuse_area(scene), 1e-5);
        if (coarse_invariants)
            check_invariants(m);
        il_patch_mesh_release(m);
    }
    s = settings_of(fine, 0);
    CHECK_OK(il_patch_mesh_build(scene, &s, &m, &err), &err);
    if (m) {
        CHECK(m->num_patches > min_fine);
        CHECK_REL(total_area(m), diffuse_area(scene), 1e-5);
        check_invariants(m);
        il_patch_mesh_release(m);
    }
}

static void test_real_scenes(void)
{
    il_error err = {0};
    il_scene *scene = NULL;
    CHECK_OK(il_scene_load("cornell", NULL, &scene, &err), &err);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    /* 5 walls, 5 + 5 block faces, the light; the red wall's published
     * corners are 3 mm out of plane. */
    check_cornell_meshing(scene, 0.05f, 500, true);
    il_scene_release(scene);

    scene = NULL;
    CHECK_OK(il_scene_load(IL_SHARED_DIR "/scenes/cornell-box-mcguire/CornellBox-Original.obj", NULL,
                           &scene, &err),
             &err);
    if (!scene)
        return;
    CHECK_OK(il_scene_commit(scene, &err), &err);
    /* Its two blocks' "bottom" faces repeat a side face (relative indices
     * in the file): meshed once.  The left wall is out of plane by 1.5 cm. */
    check_cornell_meshing(scene, 0.1f, 100, false);
    il_scene_release(scene);
}

int main(void)
{
    test_box_levels();
    test_box_one_mesh();
    test_patch_size();
    test_texture();
    test_triangle_surface();
    test_mirror();
    test_surfaces();
    test_refine();
    test_errors();
    test_tracer();
    test_real_scenes();
    return check_report();
}
