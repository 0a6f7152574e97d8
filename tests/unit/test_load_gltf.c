/* glTF 2.0 through assimp: metallic-roughness materials, emissive strength,
 * KHR_lights_punctual (photometric to radiometric), the camera and node
 * transforms, an embedded PNG texture, .glb, and corrupt files. */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "illum/illum.h"
#include "scene/scene.h"

/* One quad, (-1,-1,0)..(1,1,0): 4 float3 positions then 6 uint16 indices
 * (0 1 2 0 2 3), 60 bytes. */
#define QUAD_B64 "AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAACAPwAAgD8AAAAAAACAvwAAgD8AAAAAAAABAAIAAAACAAMA"
/* A 1x1 RGB PNG, colour (255, 128, 0). */
#define PNG_B64 "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP438AAAAQBAYDFKhhdAAAAAElFTkSuQmCC"

static const char *gltf_body =
    "\"asset\":{\"version\":\"2.0\"},"
    "\"extensionsUsed\":[\"KHR_lights_punctual\",\"KHR_materials_emissive_strength\","
    "\"KHR_materials_transmission\",\"KHR_materials_ior\"],"
    "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
    "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":12}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
    "\"min\":[-1,-1,0],\"max\":[1,1,0]},"
    "{\"bufferView\":1,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}],"
    "\"images\":[{\"uri\":\"data:image/png;base64," PNG_B64 "\"}],"
    "\"textures\":[{\"source\":0}],"
    "\"materials\":["
    "{\"name\":\"emit\",\"emissiveFactor\":[1,0.5,0.25],\"extensions\":"
    "{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":4.0}},"
    "\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.2,0.3,0.4,1],\"metallicFactor\":0}},"
    "{\"name\":\"metal\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.9,0.8,0.7,1],"
    "\"metallicFactor\":1,\"roughnessFactor\":0.02}},"
    "{\"name\":\"rough\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.9,0.8,0.7,1],"
    "\"metallicFactor\":1,\"roughnessFactor\":0.5}},"
    "{\"name\":\"glass\",\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"roughnessFactor\":0},"
    "\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1.0},"
    "\"KHR_materials_ior\":{\"ior\":1.33}}},"
    "{\"name\":\"textured\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.5,0.5,1],"
    "\"metallicFactor\":0,\"baseColorTexture\":{\"index\":0}}}],"
    "\"meshes\":["
    "{\"name\":\"m0\",\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":0}]},"
    "{\"name\":\"m1\",\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":1}]},"
    "{\"name\":\"m2\",\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":2}]},"
    "{\"name\":\"m3\",\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":3}]},"
    "{\"name\":\"m4\",\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":4}]}],"
    "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":["
    "{\"name\":\"pt\",\"type\":\"point\",\"color\":[1,0.5,0.25],\"intensity\":683},"
    "{\"name\":\"sp\",\"type\":\"spot\",\"color\":[1,1,1],\"intensity\":1366,"
    "\"spot\":{\"innerConeAngle\":0.2,\"outerConeAngle\":0.6}},"
    "{\"name\":\"sun\",\"type\":\"directional\",\"color\":[0.5,1,1],\"intensity\":3}]}},"
    "\"cameras\":[{\"name\":\"cam\",\"type\":\"perspective\","
    "\"perspective\":{\"yfov\":0.8,\"aspectRatio\":1.5,\"znear\":0.1}}],"
    "\"nodes\":["
    "{\"mesh\":0,\"translation\":[0,0,-5]},"
    "{\"mesh\":1,\"translation\":[3,0,-5]},"
    "{\"mesh\":2,\"scale\":[2,2,2]},"
    "{\"mesh\":3},"
    "{\"mesh\":4,\"translation\":[0,-1,0]},"
    "{\"name\":\"ptn\",\"translation\":[1,2,3],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
    "{\"name\":\"spn\",\"translation\":[0,4,0],\"rotation\":[-0.70710678,0,0,0.70710678],"
    "\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
    "{\"name\":\"sunn\",\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}},"
    "{\"name\":\"camn\",\"translation\":[0,1,10],\"rotation\":[0,0.70710678,0,0.70710678],"
    "\"camera\":0}],"
    "\"scenes\":[{\"nodes\":[0,1,2,3,4,5,6,7,8]}],\"scene\":0";

static const char *tmp(const char *name)
{
    static char buf[8][1024];
    static int k;
    k = (k + 1) % 8;
    snprintf(buf[k], sizeof buf[k], "%s/%s", check_tmp_dir(), name);
    return buf[k];
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

static bool contains(const char *s, const char *sub) { return s && strstr(s, sub) != NULL; }

static const il_material *find_material(const il_scene *s, const char *name)
{
    for (uint32_t i = 0; i < s->num_materials; i++)
        if (strcmp(s->materials[i].name, name) == 0)
            return &s->materials[i];
    return NULL;
}

static char *gltf_text(const char *buffers)
{
    size_t n = strlen(gltf_body) + strlen(buffers) + 16;
    char *t = malloc(n);
    snprintf(t, n, "{%s,%s}", buffers, gltf_body);
    return t;
}

static void check_scene(il_scene *s)
{
    il_scene_info info;
    il_scene_get_info(s, &info);
    CHECK(info.num_triangles == 10);
    CHECK(info.num_meshes == 5);
    CHECK(info.num_emissive_triangles == 2);
    CHECK(info.dropped_triangles == 0);
    /* Node transforms: m0 at z=-5, m1 at x in [2,4], m2 scaled by 2. */
    CHECK_NEAR(info.bounds_min.x, -2, 1e-6);
    CHECK_NEAR(info.bounds_max.x, 4, 1e-6);
    CHECK_NEAR(info.bounds_min.y, -2, 1e-6);
    CHECK_NEAR(info.bounds_max.y, 2, 1e-6);
    CHECK_NEAR(info.bounds_min.z, -5, 1e-6);
    CHECK_NEAR(info.bounds_max.z, 0, 1e-6);

    /* Materials (docs/scene-format.md, "Materials from OBJ/MTL and glTF"). */
    const il_material *m = find_material(s, "emit");
    CHECK(m && m->type == IL_MATERIAL_DIFFUSE);
    if (m) {
        /* emissiveFactor x KHR_materials_emissive_strength */
        CHECK_NEAR(m->emission.x, 4.0, 1e-6);
        CHECK_NEAR(m->emission.y, 2.0, 1e-6);
        CHECK_NEAR(m->emission.z, 1.0, 1e-6);
        CHECK_NEAR(m->diffuse.y, 0.3, 1e-6);
    }
    m = find_material(s, "metal"); /* metallic 1, roughness 0.02 */
    CHECK(m && m->type == IL_MATERIAL_MIRROR);
    if (m)
        CHECK_NEAR(m->specular.z, 0.7, 1e-6);
    m = find_material(s, "rough"); /* alpha = 0.25, n = 2/alpha^2 - 2 = 30 */
    CHECK(m && m->type == IL_MATERIAL_PHONG);
    if (m) {
        CHECK_NEAR(m->exponent, 30.0, 1e-3);
        CHECK_NEAR(m->specular.x, 0.9, 1e-6);
        CHECK_NEAR(m->diffuse.x, 0.0, 1e-6);
    }
    /* Transmission on the file's one quad, an open sheet: a thin pane of
     * its ior (glTF's transmission is thin-walled without a volume), with a
     * warning; untinted, so clear. */
    m = find_material(s, "glass");
    CHECK(m && m->type == IL_MATERIAL_THIN_GLASS);
    if (m) {
        CHECK_NEAR(m->ior, 1.33, 1e-6);
        CHECK_NEAR(m->pane_tau, 1.0, 0);
    }
    CHECK(s->num_warnings == 1 && strstr(s->warnings[0], "'glass' is transparent on an open mesh"));
    m = find_material(s, "textured");
    CHECK(m && m->type == IL_MATERIAL_DIFFUSE && m->diffuse_texture == 1);
    CHECK(info.num_textures == 1);
    if (m && m->diffuse_texture == 1) {
        /* sRGB (255, 128, 0) decoded to linear, times the factor 0.5. */
        il_vec3 c = il_material_diffuse(s, m, v2(0.5f, 0.5f));
        CHECK_NEAR(c.x, 0.5, 1e-4);
        CHECK_NEAR(c.y, 0.5 * 0.2158605, 1e-4);
        CHECK_NEAR(c.z, 0.0, 1e-6);
    }

    /* KHR_lights_punctual: candela and lux divided by 683 lm/W. */
    CHECK(s->num_user_lights == 3);
    for (uint32_t i = 0; i < s->num_user_lights; i++) {
        const il_light_desc *l = &s->user_lights[i];
        if (l->type == IL_LIGHT_POINT) {
            CHECK_NEAR(l->position.x, 1, 1e-6);
            CHECK_NEAR(l->position.y, 2, 1e-6);
            CHECK_NEAR(l->position.z, 3, 1e-6);
            CHECK_NEAR(l->intensity.x, 1.0, 1e-6);
            CHECK_NEAR(l->intensity.y, 0.5, 1e-6);
            CHECK_NEAR(l->intensity.z, 0.25, 1e-6);
        } else if (l->type == IL_LIGHT_SPOT) {
            CHECK_NEAR(l->position.y, 4, 1e-6);
            /* -90 degrees about x turns the light's -z axis to -y. */
            CHECK_NEAR(l->direction.x, 0, 1e-6);
            CHECK_NEAR(l->direction.y, -1, 1e-6);
            CHECK_NEAR(l->direction.z, 0, 1e-6);
            CHECK_NEAR(l->intensity.x, 2.0, 1e-6);
            CHECK_NEAR(l->spot_angle, 0.6 * 180.0 / 3.14159265358979, 1e-4);
            CHECK(l->spot_exponent == 0.0f);
        } else {
            CHECK(l->type == IL_LIGHT_DIRECTIONAL);
            CHECK_NEAR(l->direction.z, -1, 1e-6);
            CHECK_NEAR(l->intensity.x, 1.5 / 683.0, 1e-9);
            CHECK_NEAR(l->intensity.y, 3.0 / 683.0, 1e-9);
        }
    }

    /* The camera: at its node's origin, turned 90 degrees about y so it looks
     * down -x; yfov 0.8 rad. */
    il_camera_desc c;
    CHECK(il_scene_get_camera(s, &c));
    CHECK_NEAR(c.position.x, 0, 1e-5);
    CHECK_NEAR(c.position.y, 1, 1e-5);
    CHECK_NEAR(c.position.z, 10, 1e-5);
    il_vec3 dir = v3_normalize(v3_sub(c.target, c.position));
    CHECK_NEAR(dir.x, -1, 1e-5);
    CHECK_NEAR(dir.z, 0, 1e-5);
    CHECK_NEAR(c.up.y, 1, 1e-5);
    CHECK_NEAR(c.fov_y, 0.8 * 180.0 / 3.14159265358979, 1e-3);
}

static void test_gltf(void)
{
    char *t = gltf_text("\"buffers\":[{\"byteLength\":60,\"uri\":"
                        "\"data:application/octet-stream;base64," QUAD_B64 "\"}]");
    write_file(tmp("lights.gltf"), t, strlen(t));
    free(t);
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_load(tmp("lights.gltf"), NULL, &s, &err), &err);
    if (!s)
        return;
    check_scene(s);
    CHECK_OK(il_scene_commit(s, &err), &err);
    il_scene_release(s);
}

/* The same scene as a .glb: the JSON chunk, then the BIN chunk. */
static void test_glb(void)
{
    static const unsigned char quad[60] = {
        0x00, 0x00, 0x80, 0xbf, 0x00, 0x00, 0x80, 0xbf, 0, 0, 0, 0,
        0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x80, 0xbf, 0, 0, 0, 0,
        0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x80, 0x3f, 0, 0, 0, 0,
        0x00, 0x00, 0x80, 0xbf, 0x00, 0x00, 0x80, 0x3f, 0, 0, 0, 0,
        0, 0, 1, 0, 2, 0, 0, 0, 2, 0, 3, 0};
    char *json = gltf_text("\"buffers\":[{\"byteLength\":60}]");
    size_t jn = strlen(json), jpad = (jn + 3) & ~(size_t)3;
    size_t total = 12 + 8 + jpad + 8 + sizeof quad;
    unsigned char *glb = calloc(total, 1);
    uint32_t words[5] = {0x46546C67u, 2, (uint32_t)total, (uint32_t)jpad, 0x4E4F534Au};
    memcpy(glb, words, sizeof words); /* little-endian host assumed, as glTF is */
    memcpy(glb + 20, json, jn);
    memset(glb + 20 + jn, ' ', jpad - jn);
    uint32_t bin[2] = {sizeof quad, 0x004E4942u};
    memcpy(glb + 20 + jpad, bin, sizeof bin);
    memcpy(glb + 28 + jpad, quad, sizeof quad);
    write_file(tmp("lights.glb"), glb, total);
    free(glb);
    free(json);
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_load(tmp("lights.glb"), NULL, &s, &err), &err);
    if (!s)
        return;
    check_scene(s);
    il_scene_release(s);
}

static void test_corrupt(void)
{
    il_error err = {0};
    il_scene *s = NULL;
    /* Broken JSON: cut in the middle. */
    char *t = gltf_text("\"buffers\":[{\"byteLength\":60,\"uri\":"
                        "\"data:application/octet-stream;base64," QUAD_B64 "\"}]");
    write_file(tmp("cut.gltf"), t, strlen(t) / 2);
    CHECK(il_scene_load(tmp("cut.gltf"), NULL, &s, &err) == IL_ERR_FORMAT);
    CHECK(s == NULL);
    CHECK(contains(err.message, "cut.gltf: broken glTF JSON"));
    free(t);
    /* The buffer holds 30 bytes where 60 are declared and used. */
    t = gltf_text("\"buffers\":[{\"byteLength\":60,\"uri\":"
                  "\"data:application/octet-stream;base64,AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAACAPwAA\"}]");
    write_file(tmp("short.gltf"), t, strlen(t));
    CHECK(il_scene_load(tmp("short.gltf"), NULL, &s, &err) == IL_ERR_FORMAT);
    CHECK(s == NULL);
    CHECK(contains(err.message, "short.gltf: buffers[0] claims 60 bytes, but holds 30"));
    free(t);
    /* Byte ranges assimp would trust (il_gltf_check): a bufferView offset
     * of 2^64 - 1 (assimp copied from before its buffer), one past its
     * buffer, an accessor past its view, a view of a missing buffer. */
    const char *ranges[][3] = {
        {"\"byteOffset\":0,\"byteLength\":48", "\"byteOffset\":18446744073709551615,\"byteLength\":48",
         "bufferViews[0].byteOffset is out of range"},
        {"\"byteOffset\":48,\"byteLength\":12", "\"byteOffset\":52,\"byteLength\":12",
         "bufferViews[1] (bytes 52 to 64) runs past its buffer's 60 bytes"},
        {"\"count\":6,", "\"count\":4294967295,", "accessors[1]: 4294967295 elements"},
        {"\"buffer\":0,\"byteOffset\":48", "\"buffer\":3,\"byteOffset\":48",
         "bufferViews[1].buffer 3: there are 1 buffers"}};
    for (size_t k = 0; k < sizeof ranges / sizeof ranges[0]; k++) {
        t = gltf_text("\"buffers\":[{\"byteLength\":60,\"uri\":"
                      "\"data:application/octet-stream;base64," QUAD_B64 "\"}]");
        char *at = strstr(t, ranges[k][0]);
        CHECK(at != NULL);
        if (at) {
            size_t n = strlen(t) + 64;
            char *u = malloc(n);
            snprintf(u, n, "%.*s%s%s", (int)(at - t), t, ranges[k][1], at + strlen(ranges[k][0]));
            write_file(tmp("range.gltf"), u, strlen(u));
            CHECK(il_scene_load(tmp("range.gltf"), NULL, &s, &err) == IL_ERR_FORMAT);
            CHECK(contains(err.message, ranges[k][2]));
            printf("%s\n", err.message);
            free(u);
        }
        free(t);
    }
    /* An accessor reading past the end of its buffer view. */
    t = gltf_text("\"buffers\":[{\"byteLength\":60,\"uri\":"
                  "\"data:application/octet-stream;base64," QUAD_B64 "\"}]");
    char *count = strstr(t, "\"count\":4");
    CHECK(count != NULL);
    if (count)
        memcpy(count, "\"count\":9", 9);
    write_file(tmp("overrun.gltf"), t, strlen(t));
    il_status st = il_scene_load(tmp("overrun.gltf"), NULL, &s, &err);
    CHECK(st == IL_ERR_FORMAT);
    CHECK(contains(err.message, "overrun.gltf: "));
    if (st == IL_OK)
        il_scene_release(s);
    free(t);
    /* A .glb that is only a header. */
    const unsigned char head[12] = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 200, 0, 0, 0};
    write_file(tmp("head.glb"), head, sizeof head);
    CHECK(il_scene_load(tmp("head.glb"), NULL, &s, &err) == IL_ERR_FORMAT);
    CHECK(contains(err.message, "head.glb: truncated GLB"));
    /* A GLB whose JSON chunk claims 2 GB (assimp allocated it first). */
    const unsigned char big[28] = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 28, 0, 0, 0,
                                   0xff, 0xff, 0xff, 0x7f, 'J', 'S', 'O', 'N', '{', '}', ' ', ' ', ' ', ' ', ' ', ' '};
    write_file(tmp("big.glb"), big, sizeof big);
    CHECK(il_scene_load(tmp("big.glb"), NULL, &s, &err) == IL_ERR_FORMAT);
    CHECK(contains(err.message, "claims 2147483647 bytes"));
}

int main(void)
{
    test_gltf();
    test_glb();
    test_corrupt();
    return check_report();
}
