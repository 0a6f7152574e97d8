/* Loading mesh files through assimp: McGuire's Cornell boxes (counts, bounds,
 * the MTL material mapping), the Stanford bunny (PLY), a 3DS round trip, and
 * bad input (missing, truncated, corrupt files, NaN and degenerate
 * triangles, missing textures). */
#include <assimp/cexport.h>
#include <assimp/cimport.h>
#include <assimp/scene.h>
#include <float.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "illum/illum.h"
#include "scene/scene.h"

#define MCGUIRE IL_SHARED_DIR "/scenes/cornell-box-mcguire/"

static const il_material *find_material(const il_scene *s, const char *name)
{
    for (uint32_t i = 0; i < s->num_materials; i++)
        if (strcmp(s->materials[i].name, name) == 0)
            return &s->materials[i];
    return NULL;
}

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "cannot write %s\n", path);
        exit(2);
    }
    fwrite(data, 1, n, f);
    fclose(f);
}

static void write_text(const char *path, const char *text) { write_file(path, text, strlen(text)); }

static const char *tmp(const char *name)
{
    static char buf[8][1024];
    static int k;
    k = (k + 1) % 8;
    snprintf(buf[k], sizeof buf[k], "%s/%s", check_tmp_dir(), name);
    return buf[k];
}

static bool contains(const char *s, const char *sub) { return s && strstr(s, sub) != NULL; }

static bool any_warning_contains(const il_scene *s, const char *sub)
{
    for (uint32_t i = 0; i < s->num_warnings; i++)
        if (contains(s->warnings[i], sub))
            return true;
    return false;
}

/* What the OBJ file itself says: triangles (faces fanned), the bounds of its
 * vertices, and the triangles of faces after "usemtl light". */
typedef struct obj_facts {
    unsigned triangles, light_triangles, materials;
    double lo[3], hi[3];
} obj_facts;

static obj_facts read_obj_facts(const char *path)
{
    obj_facts o = {0, 0, 0, {DBL_MAX, DBL_MAX, DBL_MAX}, {-DBL_MAX, -DBL_MAX, -DBL_MAX}};
    FILE *f = fopen(path, "r");
    CHECK(f != NULL);
    if (!f)
        return o;
    char line[1024], names[64][64];
    bool light = false;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ') {
            double p[3];
            if (sscanf(line + 2, "%lf %lf %lf", &p[0], &p[1], &p[2]) == 3)
                for (int k = 0; k < 3; k++) {
                    o.lo[k] = p[k] < o.lo[k] ? p[k] : o.lo[k];
                    o.hi[k] = p[k] > o.hi[k] ? p[k] : o.hi[k];
                }
        } else if (line[0] == 'f' && line[1] == ' ') {
            unsigned corners = 0;
            for (char *t = strtok(line + 2, " \t\r\n"); t; t = strtok(NULL, " \t\r\n"))
                corners++;
            o.triangles += corners - 2;
            if (light)
                o.light_triangles += corners - 2;
        } else if (strncmp(line, "usemtl ", 7) == 0) {
            char name[64] = "";
            sscanf(line + 7, "%63s", name);
            light = strcmp(name, "light") == 0;
            bool seen = false;
            for (unsigned i = 0; i < o.materials; i++)
                seen |= strcmp(names[i], name) == 0;
            if (!seen && o.materials < 64)
                snprintf(names[o.materials++], 64, "%s", name);
        }
    }
    fclose(f);
    return o;
}

static il_scene *load_ok(const char *path)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_load(path, NULL, &s, &err), &err);
    return s;
}

static void test_cornell_original(void)
{
    const char *path = MCGUIRE "CornellBox-Original.obj";
    obj_facts o = read_obj_facts(path);
    CHECK(o.triangles == 36); /* 18 quads, as read from the file */
    il_scene *s = load_ok(path);
    if (!s)
        return;
    il_scene_info info;
    il_scene_get_info(s, &info);
    CHECK(info.num_triangles == o.triangles);
    CHECK(info.num_emissive_triangles == o.light_triangles);
    CHECK(info.num_emissive_triangles == 2);
    CHECK(info.num_materials == o.materials + 1); /* + illum's default material 0 */
    CHECK(info.num_materials == 9);
    CHECK(info.dropped_triangles == 0);
    CHECK(info.num_warnings == 0);
    CHECK(info.num_lights == 0);
    CHECK(!info.has_camera);
    CHECK_NEAR(info.bounds_min.x, o.lo[0], 1e-6);
    CHECK_NEAR(info.bounds_min.y, o.lo[1], 1e-6);
    CHECK_NEAR(info.bounds_min.z, o.lo[2], 1e-6);
    CHECK_NEAR(info.bounds_max.x, o.hi[0], 1e-6);
    CHECK_NEAR(info.bounds_max.y, o.hi[1], 1e-6);
    CHECK_NEAR(info.bounds_max.z, o.hi[2], 1e-6);
    CHECK_NEAR(info.bounds_min.x, -1.02, 1e-6);
    CHECK_NEAR(info.bounds_max.y, 1.99, 1e-6);

    const il_material *light = find_material(s, "light");
    const il_material *red = find_material(s, "leftWall");
    CHECK(light && red);
    if (light && red) {
        CHECK(light->type == IL_MATERIAL_DIFFUSE);
        CHECK_NEAR(light->emission.x, 17, 0);
        CHECK_NEAR(light->emission.y, 12, 0);
        CHECK_NEAR(light->emission.z, 4, 0);
        CHECK_NEAR(light->diffuse.x, 0.78f, 0);
        CHECK(red->type == IL_MATERIAL_DIFFUSE); /* Ks 0 */
        CHECK_NEAR(red->diffuse.x, 0.63f, 0);
        CHECK_NEAR(red->diffuse.y, 0.065f, 0);
        CHECK_NEAR(red->diffuse.z, 0.05f, 0);
        CHECK(v3_is_zero(red->emission));
    }
    /* No normals in the file: flat shading (no generated normals). */
    for (uint32_t i = 0; i < s->num_meshes; i++)
        CHECK(s->meshes[i].normals == NULL);

    /* End to end through commit: the emissive triangles are the lights. */
    il_error err = {0};
    CHECK_OK(il_scene_commit(s, &err), &err);
    il_scene_release(s);
}

static void test_mtl_mapping(void)
{
    il_scene *s = load_ok(MCGUIRE "CornellBox-Mirror.obj");
    if (s) {
        const il_material *m = find_material(s, "tallBox"); /* Ks .95, Ns 1000, illum 5 */
        CHECK(m && m->type == IL_MATERIAL_MIRROR);
        if (m)
            CHECK_NEAR(m->specular.x, 0.95f, 0);
        m = find_material(s, "shortBox");
        CHECK(m && m->type == IL_MATERIAL_DIFFUSE);
        il_scene_release(s);
    }
    s = load_ok(MCGUIRE "CornellBox-Sphere.obj");
    if (s) {
        const il_material *m = find_material(s, "leftSphere");
        CHECK(m && m->type == IL_MATERIAL_MIRROR);
        m = find_material(s, "rightSphere"); /* illum 7, Ni 2.5 */
        CHECK(m && m->type == IL_MATERIAL_DIELECTRIC);
        if (m) {
            CHECK_NEAR(m->ior, 2.5f, 0);
            CHECK_NEAR(m->specular.y, 1.0f, 0); /* untinted glass */
        }
        m = find_material(s, "light"); /* d 1, Tr 0, Tf 1 1 1, illum 2: opaque */
        CHECK(m && m->emission.x == 10.0f && m->emission.z == 10.0f);
        CHECK(m && m->type == IL_MATERIAL_DIFFUSE);
        m = find_material(s, "rightWall");
        CHECK(m && m->type == IL_MATERIAL_DIFFUSE);
        il_scene_info info;
        il_scene_get_info(s, &info);
        CHECK(info.dropped_triangles == 0);
        /* The spheres come with normals. */
        bool any_normals = false;
        for (uint32_t i = 0; i < s->num_meshes; i++)
            any_normals |= s->meshes[i].normals != NULL;
        CHECK(any_normals);
        il_scene_release(s);
    }
    s = load_ok(MCGUIRE "CornellBox-Water.obj");
    if (s) {
        const il_material *m = find_material(s, "water"); /* illum 7, Ni 1.33 */
        CHECK(m && m->type == IL_MATERIAL_DIELECTRIC);
        if (m)
            CHECK_NEAR(m->ior, 1.33f, 1e-6);
        il_scene_release(s);
    }
    s = load_ok(MCGUIRE "CornellBox-Glossy.obj");
    if (s) {
        const il_material *m = find_material(s, "sphere"); /* Ks .7, Ns 32, Tf 1 1 1 */
        CHECK(m && m->type == IL_MATERIAL_PHONG);
        if (m) {
            CHECK_NEAR(m->exponent, 32, 0);
            CHECK_NEAR(m->specular.x, 0.7f, 0);
            CHECK_NEAR(m->diffuse.y, 0.631f, 0);
        }
        m = find_material(s, "floor"); /* Ks .3, Ns 80 */
        CHECK(m && m->type == IL_MATERIAL_PHONG);
        if (m)
            CHECK_NEAR(m->exponent, 80, 0);
        m = find_material(s, "ceiling");
        CHECK(m && m->type == IL_MATERIAL_DIFFUSE);
        il_scene_release(s);
    }
}

static void test_bunny_ply(void)
{
    il_scene *s = load_ok(IL_SHARED_DIR "/scenes/stanford-bunny/bun_zipper_res4.ply");
    if (!s)
        return;
    il_scene_info info;
    il_scene_get_info(s, &info);
    /* The header says "element face 948"; every face is a triangle. */
    CHECK(info.num_triangles + info.dropped_triangles == 948);
    CHECK(info.num_triangles >= 940);
    CHECK(info.num_meshes == 1);
    CHECK(s->meshes[0].normals == NULL);
    CHECK(info.bounds_max.y > 0.15f && info.bounds_max.y < 0.2f); /* about 0.187 */
    il_scene_release(s);
}

/* 3DS: export McGuire's box with assimp's exporter, load it back. */
static void test_3ds_round_trip(void)
{
    const char *out = tmp("cornell.3ds");
    const struct aiScene *ai = aiImportFile(MCGUIRE "CornellBox-Original.obj", 0);
    CHECK(ai != NULL);
    if (!ai)
        return;
    enum aiReturn r = aiExportScene(ai, "3ds", out, 0);
    aiReleaseImport(ai);
    CHECK(r == aiReturn_SUCCESS);
    if (r != aiReturn_SUCCESS)
        return;
    il_scene *s = load_ok(out);
    if (!s)
        return;
    il_scene_info info;
    il_scene_get_info(s, &info);
    CHECK(info.num_triangles == 36);
    CHECK(info.num_emissive_triangles == 2);
    /* assimp's 3DS importer turns 3ds Max's z-up into y-up (x, z, -y) while
     * its exporter writes our y-up coordinates unchanged, so the box comes
     * back turned by -90 degrees about x: y' = z, z' = -y. */
    CHECK_NEAR(info.bounds_min.x, -1.02, 1e-5);
    CHECK_NEAR(info.bounds_max.x, 1.00, 1e-5);
    CHECK_NEAR(info.bounds_min.y, -1.04, 1e-5);
    CHECK_NEAR(info.bounds_max.y, 0.99, 1e-5);
    CHECK_NEAR(info.bounds_min.z, -1.99, 1e-5);
    CHECK_NEAR(info.bounds_max.z, 0.0, 1e-5);
    il_scene_release(s);
}

static il_status load_err(const char *path, il_error *err)
{
    il_scene *s = (il_scene *)1;
    il_status st = il_scene_load(path, NULL, &s, err);
    CHECK(s == NULL);
    if (st == IL_OK)
        il_scene_release(s);
    return st;
}

static void test_bad_files(void)
{
    il_error err = {0};
    const char *missing = tmp("no-such-file.obj");
    CHECK(load_err(missing, &err) == IL_ERR_IO);
    CHECK(contains(err.message, missing) && contains(err.message, "no such file"));
    il_scene *none = NULL;
    CHECK(il_scene_load(missing, NULL, &none, NULL) == IL_ERR_IO); /* err may be NULL */
    CHECK(none == NULL);

    /* Cut in the middle of a "v" line, then in the middle of an "f" line. */
    char *text;
    {
        FILE *f = fopen(MCGUIRE "CornellBox-Original.obj", "rb");
        CHECK(f != NULL);
        if (!f)
            return;
        text = calloc(1 << 16, 1);
        size_t n = fread(text, 1, (1 << 16) - 1, f);
        fclose(f);
        CHECK(n > 2000);
    }
    const char *cut = strstr(text, "v    0.53  0.00   0.75");
    CHECK(cut != NULL);
    if (cut) {
        write_file(tmp("cut-v.obj"), text, (size_t)(cut - text) + 12);
        CHECK(load_err(tmp("cut-v.obj"), &err) == IL_ERR_FORMAT);
        CHECK(contains(err.message, "cut-v.obj") && contains(err.message, "truncated"));
    }
    cut = strstr(text, "f -4 -3 -2 -1");
    CHECK(cut != NULL);
    if (cut) {
        write_file(tmp("cut-f.obj"), text, (size_t)(cut - text) + 7);
        CHECK(load_err(tmp("cut-f.obj"), &err) == IL_ERR_FORMAT);
        CHECK(contains(err.message, "cut-f.obj") && contains(err.message, "face"));
    }
    free(text);

    /* Garbage: binary bytes, and text assimp cannot make sense of. */
    unsigned char junk[4096];
    uint32_t x = 12345;
    for (size_t i = 0; i < sizeof junk; i++)
        junk[i] = (unsigned char)((x = x * 1664525u + 1013904223u) >> 24);
    write_file(tmp("junk.obj"), junk, sizeof junk);
    CHECK(load_err(tmp("junk.obj"), &err) == IL_ERR_FORMAT);
    CHECK(contains(err.message, "junk.obj"));
    write_file(tmp("junk.ply"), junk, sizeof junk);
    CHECK(load_err(tmp("junk.ply"), &err) == IL_ERR_FORMAT);
    CHECK(contains(err.message, "junk.ply"));
    /* assimp's own message is passed on. */
    write_text(tmp("badindex.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    CHECK(load_err(tmp("badindex.obj"), &err) == IL_ERR_FORMAT);
    CHECK(contains(err.message, "badindex.obj: OBJ:"));
    write_text(tmp("empty.obj"), "# nothing here\n");
    CHECK(load_err(tmp("empty.obj"), &err) != IL_OK);
    CHECK(contains(err.message, "empty.obj"));
    /* A directory is not a scene file. */
    CHECK(load_err(check_tmp_dir(), &err) == IL_ERR_IO);
}

/* PLY faces without vertex indices, on which assimp 5.2's triangulation
 * aborts the program: dropped with a warning; a mesh of nothing but such
 * faces is an error. */
static void test_empty_faces(void)
{
    const char *head = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                       "property float z\nelement face %d\nproperty list uchar int vertex_indices\n"
                       "end_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n%s";
    char text[512];
    snprintf(text, sizeof text, head, 3, "3 0 1 2\n0\n4 0 1 3 2\n");
    write_text(tmp("empty-face.ply"), text);
    il_scene *s = load_ok(tmp("empty-face.ply"));
    if (s) {
        il_scene_info info;
        il_scene_get_info(s, &info);
        CHECK(info.num_triangles == 3); /* the triangle and the quad's two */
        CHECK(any_warning_contains(s, "faces without vertex indices ignored (1)"));
        il_scene_release(s);
    }
    il_error err = {0};
    snprintf(text, sizeof text, head, 2, "0\n0\n");
    write_text(tmp("all-empty.ply"), text);
    CHECK(load_err(tmp("all-empty.ply"), &err) == IL_ERR_FORMAT);
    CHECK(contains(err.message, "all-empty.ply") && contains(err.message, "vertex indices"));
}

/* A PLY whose element or list counts are more than the file can hold is
 * refused before assimp reads it (assimp would first allocate for the
 * count: 10-23 GB for these few bytes); valid files, ASCII with blank lines
 * and binary of either byte order with 4-byte list counts, still load. */
static void test_ply_counts(void)
{
    static const char verts[] = "element vertex %s\nproperty float x\nproperty float y\nproperty float z\n"
                                "element face 2\nproperty list %s int vertex_indices\nend_header\n";
    char text[512];
    il_error err = {0};

    /* ASCII: a face of 1.2e9 indices; 2e9 vertices in a 150-byte file. */
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\n");
    snprintf(text + strlen(text), sizeof text - strlen(text), verts, "3", "uchar");
    strcat(text, "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n1200000000 0 1 2\n");
    write_text(tmp("long-face.ply"), text);
    CHECK(load_err(tmp("long-face.ply"), &err) == IL_ERR_FORMAT);
    CHECK(contains(err.message, "long-face.ply") && contains(err.message, "'face'") &&
          contains(err.message, "1200000000") && contains(err.message, "corrupt or truncated"));
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\n");
    snprintf(text + strlen(text), sizeof text - strlen(text), verts, "2000000000", "uchar");
    strcat(text, "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n");
    write_text(tmp("many-vertices.ply"), text);
    CHECK(load_err(tmp("many-vertices.ply"), &err) == IL_ERR_FORMAT);
    CHECK(contains(err.message, "'vertex'") && contains(err.message, "2000000000"));

    /* A negative list count (assimp takes -3 as 4e9 values): ASCII, and a
     * binary signed char 0xFD. */
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\n");
    snprintf(text + strlen(text), sizeof text - strlen(text), verts, "3", "char");
    strcat(text, "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n-3 0 1 2\n");
    write_text(tmp("negative.ply"), text);
    CHECK(load_err(tmp("negative.ply"), &err) == IL_ERR_FORMAT);
    CHECK(contains(err.message, "'face'") && contains(err.message, "negative count"));
    {
        unsigned char buf[2048] = {0};
        int n = snprintf((char *)buf, sizeof buf, "ply\nformat binary_little_endian 1.0\n");
        n += snprintf((char *)buf + n, sizeof buf - (size_t)n, verts, "0", "char");
        buf[n] = 0xFD;               /* -3, then 1500 bytes that could hold 3 ints */
        write_file(tmp("negative-bin.ply"), buf, (size_t)n + 1500);
        CHECK(load_err(tmp("negative-bin.ply"), &err) == IL_ERR_FORMAT);
        CHECK(contains(err.message, "negative count"));
    }
    /* More elements than the check holds: refused, not let through
     * unchecked (64 empty elements, then 2e9 vertices). */
    {
        static char many[8192];
        int n = snprintf(many, sizeof many, "ply\nformat binary_little_endian 1.0\n");
        for (int k = 0; k < 64; k++)
            n += snprintf(many + n, sizeof many - (size_t)n, "element d%d 0\nproperty float a\n", k);
        snprintf(many + n, sizeof many - (size_t)n, "element vertex 2000000000\nproperty float x\nend_header\n");
        write_text(tmp("many-elements.ply"), many);
        CHECK(load_err(tmp("many-elements.ply"), &err) == IL_ERR_FORMAT);
        CHECK(contains(err.message, "more than 64 elements"));
    }

    /* Headers that are not PLY (assimp loops forever on some of them). */
    const char *bad_headers[][2] = {
        {"ply\nformat binary_little_endian 1.0\nelement vertex 4.3\nend_header\n", "whole count"},
        {"ply\nformat binary_little_endian 1.0\nelementerty float z\nend_header\n", "not a PLY header line"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float\nend_header\n", "known type"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "no end_header"},
        {"ply\nelement vertex 0\nend_header\n", "no format"},
        {"ply?\nformat ascii 1.0\nend_header\n", "not a PLY file"}};
    for (size_t i = 0; i < sizeof bad_headers / sizeof bad_headers[0]; i++) {
        write_text(tmp("bad-header.ply"), bad_headers[i][0]);
        CHECK(load_err(tmp("bad-header.ply"), &err) == IL_ERR_FORMAT);
        CHECK(contains(err.message, "bad-header.ply") && contains(err.message, bad_headers[i][1]));
    }

    /* ASCII, valid: blank lines and trailing spaces. */
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\ncomment ok\n");
    snprintf(text + strlen(text), sizeof text - strlen(text), verts, "4", "uchar");
    strcat(text, "0 0 0\n\n1 0 0 \n0 1 0\n1 1 0\r\n3 0 1 2\n3 1 3 2  \n");
    write_text(tmp("ascii-ok.ply"), text);
    il_scene *s = load_ok(tmp("ascii-ok.ply"));
    if (s) {
        CHECK(s->num_meshes == 1 && s->meshes[0].num_triangles == 2);
        il_scene_release(s);
    }

    /* Binary, both byte orders, 4-byte list counts: valid, then one face
     * claiming 1.2e9 indices, then 2e9 vertices. */
    for (int big = 0; big < 2; big++) {
        const char *name[3][2] = {{"le-ok.ply", "be-ok.ply"}, {"le-face.ply", "be-face.ply"},
                                  {"le-count.ply", "be-count.ply"}};
        for (int variant = 0; variant < 3; variant++) {
            unsigned char buf[512];
            int n = snprintf((char *)buf, sizeof buf, "ply\nformat binary_%s_endian 1.0\n",
                             big ? "big" : "little");
            n += snprintf((char *)buf + n, sizeof buf - (size_t)n, verts,
                          variant == 2 ? "2000000000" : "3", "uint");
            const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
            const uint32_t face[2][4] = {{3, 0, 1, 2}, {variant == 1 ? 1200000000u : 3u, 0, 2, 1}};
            const unsigned char *words[2] = {(const unsigned char *)xyz, (const unsigned char *)face};
            const size_t counts[2] = {9, 8};
            for (int w = 0; w < 2; w++)
                for (size_t i = 0; i < counts[w]; i++)   /* 4-byte words, host is little-endian */
                    for (int b = 0; b < 4; b++)
                        buf[n++] = words[w][4 * i + (size_t)(big ? 3 - b : b)];
            write_file(tmp(name[variant][big]), buf, (size_t)n);
            if (variant == 0) {
                s = load_ok(tmp(name[variant][big]));
                if (s) {
                    CHECK(s->num_meshes == 1 && s->meshes[0].num_triangles == 2);
                    il_scene_release(s);
                }
            } else {
                CHECK(load_err(tmp(name[variant][big]), &err) == IL_ERR_FORMAT);
                CHECK(contains(err.message, name[variant][big]) &&
                      contains(err.message, variant == 1 ? "1200000000" : "2000000000") &&
                      contains(err.message, "corrupt or truncated"));
            }
        }
    }
}

/* OFF: a header claiming 10^8 vertices and faces in a 30-byte file is
 * refused before assimp reserves gigabytes for it; a square, with its
 * counts on the keyword's line or the next, a comment between, loads. */
static void test_off_counts(void)
{
    il_error err = {0};
    write_text(tmp("huge.off"), "OFF\n99999999 99999999 0\n0 0 0\n");
    CHECK(load_err(tmp("huge.off"), &err) == IL_ERR_FORMAT);
    CHECK(contains(err.message, "huge.off") && contains(err.message, "99999999 vertices") &&
          contains(err.message, "corrupt or truncated"));
    const char *ok[] = {"OFF\n# a square\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
                        "OFF 4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"};
    for (int k = 0; k < 2; k++) {
        write_text(tmp("square.off"), ok[k]);
        il_scene *s = load_ok(tmp("square.off"));
        if (s) {
            CHECK(s->num_meshes == 1 && s->meshes[0].num_triangles == 2);
            il_scene_release(s);
        }
    }
}

static void test_nan_and_degenerate(void)
{
    il_error err = {0};
    write_text(tmp("nan.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nf 1 2 3\nf 1 2 4\n");
    il_scene *s = load_ok(tmp("nan.obj"));
    if (s) {
        il_scene_info info;
        il_scene_get_info(s, &info);
        CHECK(info.num_triangles == 1);
        CHECK(info.dropped_triangles == 1);
        CHECK(info.num_warnings == 1);
        CHECK(any_warning_contains(s, "dropped 1 of 2"));
        CHECK(info.bounds_max.x == 1.0f && info.bounds_min.x == 0.0f);
        il_scene_release(s);
    }
    /* Only degenerate triangles: a collinear one and one with a repeated corner. */
    write_text(tmp("degenerate.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n");
    CHECK(load_err(tmp("degenerate.obj"), &err) == IL_ERR_INVALID);
    CHECK(contains(err.message, "degenerate.obj: no triangles"));
}

static void test_textures(void)
{
    /* A 2x1 PFM texture (bottom-to-top rows; one row here). */
    const char hdr[] = "PF\n2 1\n-1.0\n";
    const float px[6] = {0.25f, 0.5f, 1.0f, 0.25f, 0.5f, 1.0f};
    unsigned char pfm[sizeof hdr - 1 + sizeof px];
    memcpy(pfm, hdr, sizeof hdr - 1);
    memcpy(pfm + sizeof hdr - 1, px, sizeof px);
    write_file(tmp("tex.pfm"), pfm, sizeof pfm);
    write_text(tmp("tex.mtl"), "newmtl textured\nKd 0.5 0.5 0.5\nmap_Kd tex.pfm\n"
                               "newmtl lost\nKd 0.2 0.4 0.6\nmap_Kd does-not-exist.png\n");
    write_text(tmp("tex.obj"), "mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                               "usemtl textured\nf 1/1 2/2 3/3\nusemtl lost\nf 1/1 3/3 2/2\n");
    il_scene *s = load_ok(tmp("tex.obj"));
    if (!s)
        return;
    il_scene_info info;
    il_scene_get_info(s, &info);
    CHECK(info.num_triangles == 2);
    CHECK(info.num_textures == 1);
    const il_material *t = find_material(s, "textured"), *lost = find_material(s, "lost");
    CHECK(t && lost);
    if (t && lost) {
        CHECK(t->diffuse_texture == 1);
        if (t->diffuse_texture == 1) {
            il_vec3 c = il_material_diffuse(s, t, v2(0.3f, 0.5f));
            CHECK_NEAR(c.x, 0.125f, 1e-6);
            CHECK_NEAR(c.y, 0.25f, 1e-6);
            CHECK_NEAR(c.z, 0.5f, 1e-6);
        }
        /* The missing texture: a warning naming the file, the colour stays. */
        CHECK(lost->diffuse_texture == 0);
        CHECK_NEAR(lost->diffuse.z, 0.6f, 0);
        CHECK(any_warning_contains(s, "does-not-exist.png"));
        CHECK(info.num_warnings == 1);
    }
    bool uvs = false;
    for (uint32_t i = 0; i < s->num_meshes; i++)
        uvs |= s->meshes[i].uvs != NULL;
    CHECK(uvs);
    il_scene_release(s);
}

static void test_builtin_name(void)
{
    /* A built-in name that is no file loads the built-in scene. */
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_load("cornell", NULL, &s, &err), &err);
    if (s) {
        il_scene_info info;
        il_scene_get_info(s, &info);
        CHECK(info.num_triangles > 0);
        il_scene_release(s);
    }
    CHECK(load_err("no-such-builtin", &err) == IL_ERR_IO);
    CHECK(contains(err.message, "no-such-builtin: no such file"));
}

static int log_calls;
static void count_log(il_log_level level, const char *message, void *user)
{
    (void)message;
    if (level == IL_LOG_WARNING && user == &log_calls)
        log_calls++;
}

static void test_log_callback(void)
{
    il_load_desc d = {.log = count_log, .log_user = &log_calls};
    il_error err = {0};
    il_scene *s = NULL;
    log_calls = 0;
    CHECK_OK(il_scene_load(tmp("nan.obj"), &d, &s, &err), &err);
    CHECK(log_calls == 1);
    il_scene_release(s);
}

/* A Collada camera: assimp's importers give the full horizontal angle (60
 * degrees here), which becomes fov_y = 2 atan(tan(30 deg) / 1.5). */
static void test_collada_camera(void)
{
    write_text(tmp("cam.dae"),
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
    "  <asset><unit name=\"meter\" meter=\"1\"/><up_axis>Y_UP</up_axis></asset>\n"
    "  <library_cameras>\n"
    "    <camera id=\"cam\" name=\"cam\"><optics><technique_common><perspective>\n"
    "      <xfov>60</xfov><aspect_ratio>1.5</aspect_ratio><znear>0.1</znear><zfar>100</zfar>\n"
    "    </perspective></technique_common></optics></camera>\n"
    "  </library_cameras>\n"
    "  <library_geometries>\n"
    "    <geometry id=\"tri\" name=\"tri\"><mesh>\n"
    "      <source id=\"p\"><float_array id=\"pa\" count=\"9\">0 0 0 1 0 0 0 1 0</float_array>\n"
    "        <technique_common><accessor source=\"#pa\" count=\"3\" stride=\"3\">\n"
    "          <param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/>\n"
    "        </accessor></technique_common></source>\n"
    "      <vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
    "      <triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>0 1 2</p></triangles>\n"
    "    </mesh></geometry>\n"
    "  </library_geometries>\n"
    "  <library_visual_scenes>\n"
    "    <visual_scene id=\"s\">\n"
    "      <node id=\"camnode\" name=\"camnode\"><translate>0 1 10</translate><instance_camera url=\"#cam\"/></node>\n"
    "      <node id=\"trinode\" name=\"trinode\"><instance_geometry url=\"#tri\"/></node>\n"
    "    </visual_scene>\n"
    "  </library_visual_scenes>\n"
    "  <scene><instance_visual_scene url=\"#s\"/></scene>\n"
    "</COLLADA>\n"
    );
    il_scene *s = load_ok(tmp("cam.dae"));
    if (!s)
        return;
    il_camera_desc c;
    CHECK(il_scene_get_camera(s, &c));
    CHECK_NEAR(c.position.y, 1.0, 1e-6);
    CHECK_NEAR(c.position.z, 10.0, 1e-6);
    CHECK_NEAR(c.target.z, 9.0, 1e-6);
    CHECK_NEAR(c.fov_y, 2.0 * atan(tan(30.0 * 3.14159265358979 / 180.0) / 1.5) * 180.0 /
                            3.14159265358979, 1e-3);
    il_scene_release(s);
}

/* Transparent materials that ask for no refraction (d < 1, illum 4) on an
 * open mesh (a window as one sheet) become thin panes with a warning; on a
 * closed solid (a cube whose corners repeat per face) and with illum 7
 * (refraction) they stay dielectric. */
static void test_window_panes(void)
{
    write_text(tmp("panes.mtl"), "newmtl window\nKd 0 0 0\nd 0.3\nNi 1.52\nillum 2\n"
                                 "newmtl tinted\nKd 0 0 0\nillum 4\n"
                                 "newmtl solid\nKd 0 0 0\nd 0.5\nillum 2\n"
                                 "newmtl sheet7\nNi 1.33\nillum 7\n"
                                 "newmtl wall\nKd 0.5 0.5 0.5\n");
    write_text(tmp("panes.obj"),
               "mtllib panes.mtl\n"
               "o pane\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl window\nf 1 2 3 4\n"
               "o sheet\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nusemtl sheet7\nf 5 6 7 8\n"
               "o cube\n"
               "v 2 0 0\nv 3 0 0\nv 3 1 0\nv 2 1 0\nv 2 0 1\nv 3 0 1\nv 3 1 1\nv 2 1 1\n"
               "vn 0 0 -1\nvn 0 0 1\nvn -1 0 0\nvn 1 0 0\nvn 0 -1 0\nvn 0 1 0\n"
               "usemtl solid\n"
               "f 9//1 12//1 11//1 10//1\nf 13//2 14//2 15//2 16//2\nf 9//3 13//3 16//3 12//3\n"
               "f 10//4 11//4 15//4 14//4\nf 9//5 10//5 14//5 13//5\nf 12//6 16//6 15//6 11//6\n"
               "o floor\nv -5 -1 -5\nv 5 -1 -5\nv 5 -1 5\nv -5 -1 5\nusemtl wall\nf 17 20 19 18\n");
    il_scene *s = load_ok(tmp("panes.obj"));
    if (!s)
        return;
    const char *expect[][2] = {{"pane", "thin"}, {"sheet", "dielectric"}, {"cube", "dielectric"}};
    for (int k = 0; k < 3; k++) {
        const il_material *m = NULL;
        for (uint32_t i = 0; i < s->num_meshes; i++)
            if (strcmp(s->meshes[i].name, expect[k][0]) == 0)
                m = &s->materials[s->meshes[i].material];
        bool thin = strcmp(expect[k][1], "thin") == 0;
        printf("%s: %s\n", expect[k][0], m ? (m->type == IL_MATERIAL_THIN_GLASS ? "thin_glass" : "other") : "?");
        CHECK(m && m->type == (thin ? IL_MATERIAL_THIN_GLASS : IL_MATERIAL_DIELECTRIC));
        if (m && thin)
            CHECK_NEAR(m->ior, 1.52f, 1e-6);
    }
    CHECK(any_warning_contains(s, "'window' is transparent on an open mesh ('pane'"));
    CHECK(!any_warning_contains(s, "'solid'") && !any_warning_contains(s, "'sheet7'"));
    il_scene_release(s);
}

int main(void)
{
    test_cornell_original();
    test_mtl_mapping();
    test_window_panes();
    test_bunny_ply();
    test_empty_faces();
    test_ply_counts();
    test_off_counts();
    test_3ds_round_trip();
    test_bad_files();
    test_nan_and_degenerate();
    test_textures();
    test_builtin_name();
    test_log_callback();
    test_collada_camera();
    return check_report();
}
