/* il_bake_write: a synthetic bake of two meshes written to PLY and parsed
 * back here (header, counts, exact float radiance, sRGB colour bytes,
 * offset indices), written to GLB and .gltf and re-imported with assimp
 * (counts, COLOR_0 within 1/255, COLOR_1 exact), and the error paths (an
 * unknown extension, a folder that does not exist, bad indices) leaving no
 * file behind. */
#include <dirent.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>

#include <assimp/cimport.h>
#include <assimp/mesh.h>
#include <assimp/scene.h>

#include "check.h"
#include "illum/illum.h"
#include "image/srgb.h"

/* Mesh 0: a quad (4 vertices, 2 triangles); mesh 1: one triangle.  Radiance
 * spans dark, mid, above 1 (HDR) and a value that needs all float bits. */
static float pos0[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
static float nrm0[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
static float rad0[12] = {0.0f, 0.001f, 0.5f, 0.25f, 0.18f, 0.9f, 3.5f, 1.0f, 0.0f, 0.123456789f, 7.25f, 1e-7f};
static uint32_t idx0[6] = {0, 1, 2, 0, 2, 3};
static float pos1[9] = {2, 0, 0, 3, 0, 0, 2, 0, -1};
static float nrm1[9] = {0, 1, 0, 0, 1, 0, 0, 1, 0};
static float rad1[9] = {0.75f, 0.5f, 0.25f, 100.0f, 0.0f, 0.01f, 0.3333333f, 0.6666667f, 0.0f};
static uint32_t idx1[3] = {0, 1, 2};

static il_bake_mesh meshes[2];
static il_bake_result bake;

static void make_bake(void)
{
    meshes[0] = (il_bake_mesh){.num_vertices = 4, .num_triangles = 2, .positions = pos0,
                               .normals = nrm0, .radiance = rad0, .indices = idx0, .material = 1};
    strcpy(meshes[0].name, "quad");
    meshes[1] = (il_bake_mesh){.num_vertices = 3, .num_triangles = 1, .positions = pos1,
                               .normals = nrm1, .radiance = rad1, .indices = idx1, .material = 2};
    strcpy(meshes[1].name, "tri");
    bake = (il_bake_result){.num_meshes = 2, .meshes = meshes};
}

static char *path_in_tmp(char *buf, size_t size, const char *name)
{
    snprintf(buf, size, "%s/%s", check_tmp_dir(), name);
    return buf;
}

/* Files in the test folder whose name starts with `prefix` (temporaries included). */
static int count_files(const char *prefix)
{
    DIR *d = opendir(check_tmp_dir());
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (strncmp(e->d_name, prefix, strlen(prefix)) == 0)
            n++;
    if (d)
        closedir(d);
    return n;
}

static float get_f32(const unsigned char *p)
{
    uint32_t v = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    float f;
    memcpy(&f, &v, sizeof f);
    return f;
}
static uint32_t get_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void test_ply(void)
{
    char path[512];
    path_in_tmp(path, sizeof path, "bake.ply");
    unlink(path);
    il_error err = {0};
    il_bake_write_desc wd = {.exposure = 1.0f};
    CHECK_OK(il_bake_write(&bake, path, &wd, &err), &err);
    CHECK(count_files("bake.ply") == 1); /* no temporary left */

    FILE *f = fopen(path, "rb");
    CHECK(f != NULL);
    if (!f)
        return;
    static unsigned char data[1 << 16];
    size_t size = fread(data, 1, sizeof data, f);
    fclose(f);
    const char *end = strstr((const char *)data, "end_header\n");
    CHECK(end != NULL);
    if (!end)
        return;
    size_t header = (size_t)(end - (const char *)data) + strlen("end_header\n");
    char text[4096];
    memcpy(text, data, header);
    text[header] = '\0';
    CHECK(strncmp(text, "ply\nformat binary_little_endian 1.0\n", 36) == 0);
    CHECK(strstr(text, "element vertex 7\n") != NULL);
    CHECK(strstr(text, "element face 3\n") != NULL);
    const char *props = "property float x\nproperty float y\nproperty float z\n"
                        "property float nx\nproperty float ny\nproperty float nz\n"
                        "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                        "property float radiance_r\nproperty float radiance_g\nproperty float radiance_b\n"
                        "element face 3\nproperty list uchar uint vertex_indices\nend_header\n";
    CHECK(strstr(text, props) != NULL);
    const size_t vbytes = 6 * 4 + 3 + 3 * 4, fbytes = 1 + 3 * 4;
    CHECK(size == header + 7 * vbytes + 3 * fbytes);
    if (size != header + 7 * vbytes + 3 * fbytes)
        return;

    const unsigned char *p = data + header;
    for (int v = 0; v < 7; v++, p += vbytes) {
        const float *pos = v < 4 ? pos0 + 3 * v : pos1 + 3 * (v - 4);
        const float *nrm = v < 4 ? nrm0 + 3 * v : nrm1 + 3 * (v - 4);
        const float *rad = v < 4 ? rad0 + 3 * v : rad1 + 3 * (v - 4);
        for (int k = 0; k < 3; k++) {
            CHECK(get_f32(p + 4 * k) == pos[k]);
            CHECK(get_f32(p + 12 + 4 * k) == nrm[k]);
            CHECK(get_f32(p + 27 + 4 * k) == rad[k]); /* the HDR value, bit for bit */
            /* exposure +1: twice the radiance, clamped, sRGB-encoded */
            double x = 2.0 * rad[k];
            unsigned char want = x >= 1.0 ? 255 : (unsigned char)lrint(il_linear_to_srgb(x) * 255.0);
            if (x <= 0.0)
                want = 0;
            CHECK(p[24 + k] == want);
        }
    }
    /* spot values: 0.25 * 2 = 0.5 -> sRGB 0.7354 -> 188 */
    CHECK(data[header + vbytes + 24] == 188);
    const uint32_t want_idx[9] = {0, 1, 2, 0, 2, 3, 4, 5, 6}; /* mesh 1 offset by 4 */
    for (int t = 0; t < 3; t++, p += fbytes) {
        CHECK(p[0] == 3);
        for (int k = 0; k < 3; k++)
            CHECK(get_u32(p + 1 + 4 * k) == want_idx[3 * t + k]);
    }
    /* desc NULL: exposure 0 */
    CHECK_OK(il_bake_write(&bake, path, NULL, &err), &err);
    f = fopen(path, "rb");
    if (f) {
        size = fread(data, 1, sizeof data, f);
        fclose(f);
        CHECK(data[header + vbytes + 24] == (unsigned char)lrint(il_linear_to_srgb(0.25) * 255.0));
    }
}

static void check_imported(const char *path)
{
    const struct aiScene *sc = aiImportFile(path, 0);
    CHECK(sc != NULL);
    if (!sc) {
        fprintf(stderr, "assimp: %s\n", aiGetErrorString());
        return;
    }
    CHECK(sc->mNumMeshes == 2);
    if (sc->mNumMeshes != 2) {
        aiReleaseImport(sc);
        return;
    }
    for (unsigned m = 0; m < 2; m++) {
        const struct aiMesh *am = sc->mMeshes[m];
        const il_bake_mesh *bm = &meshes[m];
        CHECK(am->mNumVertices == bm->num_vertices);
        CHECK(am->mNumFaces == bm->num_triangles);
        CHECK(am->mColors[0] != NULL);
        CHECK(am->mColors[1] != NULL);
        CHECK(am->mNormals != NULL);
        if (am->mNumVertices != bm->num_vertices || !am->mColors[0] || !am->mColors[1] || !am->mNormals)
            continue;
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            const float *r = bm->radiance + 3 * v, *p = bm->positions + 3 * v;
            CHECK(am->mVertices[v].x == p[0] && am->mVertices[v].y == p[1] && am->mVertices[v].z == p[2]);
            /* exposure 0 here: COLOR_0 is the radiance clamped to [0,1] */
            CHECK_NEAR(am->mColors[0][v].r, fmin(r[0], 1.0), 1.0 / 255.0);
            CHECK_NEAR(am->mColors[0][v].g, fmin(r[1], 1.0), 1.0 / 255.0);
            CHECK_NEAR(am->mColors[0][v].b, fmin(r[2], 1.0), 1.0 / 255.0);
            CHECK(am->mColors[1][v].r == r[0] && am->mColors[1][v].g == r[1] &&
                  am->mColors[1][v].b == r[2]);
            CHECK(am->mColors[1][v].a == 1.0f);
        }
        for (unsigned t = 0; t < am->mNumFaces; t++) {
            CHECK(am->mFaces[t].mNumIndices == 3);
            if (am->mFaces[t].mNumIndices == 3)
                for (int k = 0; k < 3; k++)
                    CHECK(am->mFaces[t].mIndices[k] == bm->indices[3 * t + k]);
        }
    }
    aiReleaseImport(sc);
}

static void test_gltf(void)
{
    char path[512];
    il_error err = {0};
    path_in_tmp(path, sizeof path, "bake.glb");
    unlink(path);
    CHECK_OK(il_bake_write(&bake, path, NULL, &err), &err);
    CHECK(count_files("bake.glb") == 1);
    check_imported(path);

    path_in_tmp(path, sizeof path, "text.gltf");
    CHECK_OK(il_bake_write(&bake, path, NULL, &err), &err);
    CHECK(count_files("text.gltf") == 1);
    check_imported(path);
}

static void test_errors(void)
{
    char path[512];
    il_error err = {0};
    path_in_tmp(path, sizeof path, "bake.txt");
    CHECK(il_bake_write(&bake, path, NULL, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "bake.txt") != NULL);
    CHECK(count_files("bake.txt") == 0);
    CHECK(il_bake_write(&bake, "noextension", NULL, &err) == IL_ERR_INVALID);

    const char *names[3] = {"missing/x.ply", "missing/x.glb", "missing/x.gltf"};
    for (int i = 0; i < 3; i++) {
        path_in_tmp(path, sizeof path, names[i]);
        CHECK(il_bake_write(&bake, path, NULL, &err) == IL_ERR_IO);
        CHECK(strstr(err.message, "missing/x") != NULL);
        CHECK(count_files("missing") == 0);
    }

    /* An index beyond the vertices is refused before anything is written. */
    uint32_t bad[3] = {0, 1, 9};
    il_bake_mesh m = meshes[1];
    m.indices = bad;
    il_bake_result b = {.num_meshes = 1, .meshes = &m};
    path_in_tmp(path, sizeof path, "badindex.ply");
    CHECK(il_bake_write(&b, path, NULL, &err) == IL_ERR_INVALID);
    CHECK(count_files("badindex.ply") == 0);
    il_bake_write_desc wd = {.exposure = NAN};
    path_in_tmp(path, sizeof path, "nan.ply");
    CHECK(il_bake_write(&bake, path, &wd, &err) == IL_ERR_INVALID);
    CHECK(count_files("nan.ply") == 0);
}

int main(void)
{
    make_bake();
    test_ply();
    test_gltf();
    test_errors();
    return check_report();
}
