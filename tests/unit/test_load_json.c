/* JSON scene files: transforms, inline meshes and shapes, materials and
 * overrides, lights, camera, environment, render settings, and errors that
 * name the file and the key. */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "illum/illum.h"
#include "scene/pane.h"
#include "scene/scene.h"

static const char *tmp(const char *name)
{
    static char buf[8][1024];
    static int k;
    k = (k + 1) % 8;
    snprintf(buf[k], sizeof buf[k], "%s/%s", check_tmp_dir(), name);
    return buf[k];
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "cannot write %s\n", path);
        exit(2);
    }
    fputs(text, f);
    fclose(f);
}

static bool contains(const char *s, const char *sub) { return s && strstr(s, sub) != NULL; }

static bool any_warning_contains(const il_scene *s, const char *sub)
{
    for (uint32_t i = 0; i < s->num_warnings; i++)
        if (contains(s->warnings[i], sub))
            return true;
    return false;
}

static const il_material *find_material(const il_scene *s, const char *name)
{
    for (uint32_t i = 0; i < s->num_materials; i++)
        if (strcmp(s->materials[i].name, name) == 0)
            return &s->materials[i];
    return NULL;
}

static const il_mesh *find_mesh(const il_scene *s, const char *name)
{
    for (uint32_t i = 0; i < s->num_meshes; i++)
        if (strcmp(s->meshes[i].name, name) == 0)
            return &s->meshes[i];
    return NULL;
}

/* Loads JSON text written to tmp/name. */
static il_scene *load_json(const char *name, const char *json, il_status *st, il_error *err)
{
    write_text(tmp(name), json);
    il_scene *s = NULL;
    *st = il_scene_load(tmp(name), NULL, &s, err);
    return s;
}

static il_scene *load_json_ok(const char *name, const char *json)
{
    il_error err = {0};
    il_status st;
    il_scene *s = load_json(name, json, &st, &err);
    CHECK_OK(st, &err);
    return s;
}

/* The geometric normal of triangle t of a mesh, from its winding. */
static il_vec3 face_normal(const il_mesh *m, uint32_t t)
{
    const uint32_t *i = m->indices + 3 * t;
    il_vec3 a = m->positions[i[0]], b = m->positions[i[1]], c = m->positions[i[2]];
    return v3_normalize(v3_cross(v3_sub(b, a), v3_sub(c, a)));
}

static void test_full_scene(void)
{
    il_scene *s = load_json_ok("full.json", "{\n"
        "\"materials\": {\n"
        "  \"red\": {\"type\": \"diffuse\", \"diffuse\": [0.8, 0.1, 0.1]},\n"
        "  \"shiny\": {\"type\": \"phong\", \"diffuse\": 0.2, \"specular\": [0.5,0.5,0.5], \"exponent\": 50},\n"
        "  \"glass\": {\"type\": \"dielectric\", \"ior\": 1.7},\n"
        "  \"chrome\": {\"type\": \"mirror\"},\n"
        "  \"window\": {\"type\": \"thin_glass\", \"ior\": 1.52, \"transmittance\": 0.7},\n"
        "  \"lamp\": {\"emission\": [5, 4, 3], \"two_sided\": true}\n"
        "},\n"
        "\"meshes\": [\n"
        "  {\"name\": \"tri\", \"positions\": [0,0,0, 1,0,0, 0,1,0], \"indices\": [0,1,2],\n"
        "   \"material\": \"red\", \"transform\": {\"translate\": [10, 0, 0], \"scale\": 2}},\n"
        "  {\"name\": \"soup\", \"positions\": [0,0,0, 1,0,0, 0,0,-1], \"normals\": [0,1,0, 0,1,0, 0,1,0],\n"
        "   \"uvs\": [0,0, 1,0, 0,1], \"material\": \"shiny\"},\n"
        "  {\"shape\": \"box\", \"size\": [2, 4, 6], \"material\": \"glass\",\n"
        "   \"matrix\": [1,0,0,0, 0,1,0,20, 0,0,1,0, 0,0,0,1]},\n"
        "  {\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 2, \"segments\": 16, \"material\": \"chrome\"},\n"
        "  {\"name\": \"lampquad\", \"shape\": \"quad\", \"size\": [2, 3], \"material\": \"lamp\", \"flip\": true,\n"
        "   \"transform\": {\"translate\": [0, 5, 0]}}\n"
        "],\n"
        "\"lights\": [\n"
        "  {\"type\": \"point\", \"position\": [1, 2, 3], \"intensity\": 7},\n"
        "  {\"type\": \"spot\", \"position\": [0, 4, 0], \"direction\": [0, -2, 0], \"intensity\": [1, 2, 3],\n"
        "   \"angle\": 25, \"exponent\": 8},\n"
        "  {\"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": [3, 3, 3], \"diameter\": 2.5}\n"
        "],\n"
        "\"camera\": {\"position\": [0, 1, 8], \"target\": [0, 1, 0], \"up\": [0, 1, 0], \"fov\": 35},\n"
        "\"environment\": {\"radiance\": [0.1, 0.2, 0.3]},\n"
        "\"render\": {\"width\": 320, \"height\": 240, \"spp\": 32, \"max_depth\": 5, \"seed\": 7,\n"
        "            \"method\": \"pt\", \"time\": 2.5}\n"
        "}\n");
    if (!s)
        return;
    il_scene_info info;
    il_scene_get_info(s, &info);
    CHECK(info.num_meshes == 5);
    /* 1 + 1 + 12 + sphere (2*16*(8-1) = 224) + 2 */
    CHECK(info.num_triangles == 1 + 1 + 12 + 224 + 2);
    CHECK(info.num_materials == 7);
    CHECK(info.num_lights == 3);
    CHECK(info.has_environment);
    CHECK(info.has_camera);
    CHECK(info.num_warnings == 0);
    CHECK(info.dropped_triangles == 0);
    CHECK(info.num_emissive_triangles == 2);

    for (uint32_t i = 0; i < s->num_materials; i++)
        if (strcmp(s->materials[i].name, "window") == 0) {
            const il_material *w = &s->materials[i];
            float R, T;
            il_pane_optics(w->ior, w->pane_tau, 1.0f, &R, &T);
            CHECK(w->type == IL_MATERIAL_THIN_GLASS && w->ior == 1.52f);
            CHECK_NEAR(T, 0.7, 1e-5);
        }
    const il_mesh *tri = find_mesh(s, "tri");
    CHECK(tri != NULL);
    if (tri) {
        /* Scaled by 2 about the origin, then moved by +10 in x. */
        CHECK_NEAR(tri->positions[1].x, 12.0, 1e-6);
        CHECK_NEAR(tri->positions[2].y, 2.0, 1e-6);
        CHECK(strcmp(s->materials[tri->material].name, "red") == 0);
    }
    const il_mesh *soup = find_mesh(s, "soup");
    CHECK(soup && soup->normals && soup->uvs);
    if (soup && soup->normals)
        CHECK_NEAR(soup->normals[0].y, 1.0, 0);
    const il_mesh *box = find_mesh(s, "box");
    CHECK(box != NULL);
    if (box) {
        il_vec3 lo = v3s(1e30f), hi = v3s(-1e30f);
        for (uint32_t v = 0; v < box->num_vertices; v++) {
            lo = v3_min(lo, box->positions[v]);
            hi = v3_max(hi, box->positions[v]);
        }
        CHECK_NEAR(lo.x, -1, 1e-6);
        CHECK_NEAR(hi.y, 22, 1e-6); /* matrix: +20 in y */
        CHECK_NEAR(lo.z, -3, 1e-6);
        /* Outward faces: every face normal points away from the centre. */
        il_vec3 centre = v3(0, 20, 0);
        bool outward = true;
        for (uint32_t t = 0; t < box->num_triangles; t++) {
            const uint32_t *i = box->indices + 3 * t;
            il_vec3 mid = v3_scale(v3_add(v3_add(box->positions[i[0]], box->positions[i[1]]),
                                          box->positions[i[2]]), 1.0f / 3.0f);
            outward &= v3_dot(face_normal(box, t), v3_sub(mid, centre)) > 0;
        }
        CHECK(outward);
    }
    const il_mesh *ball = find_mesh(s, "ball");
    CHECK(ball && ball->normals);
    if (ball && ball->normals) {
        bool on_sphere = true, outward = true;
        for (uint32_t v = 0; v < ball->num_vertices; v++)
            on_sphere &= fabsf(v3_length(ball->positions[v]) - 2.0f) < 1e-5f;
        for (uint32_t t = 0; t < ball->num_triangles; t++)
            outward &= v3_dot(face_normal(ball, t), ball->positions[ball->indices[3 * t]]) > 0;
        CHECK(on_sphere);
        CHECK(outward);
    }
    const il_mesh *lamp = find_mesh(s, "lampquad");
    CHECK(lamp != NULL);
    if (lamp) {
        CHECK_NEAR(face_normal(lamp, 0).y, -1.0, 1e-6); /* flipped: faces down */
        CHECK_NEAR(lamp->positions[0].y, 5.0, 0);
        const il_material *m = &s->materials[lamp->material];
        CHECK(m->two_sided && m->emission.x == 5.0f);
    }
    const il_material *m = find_material(s, "shiny");
    CHECK(m && m->type == IL_MATERIAL_PHONG && m->exponent == 50.0f && m->diffuse.x == 0.2f);
    m = find_material(s, "glass");
    CHECK(m && m->type == IL_MATERIAL_DIELECTRIC && m->ior == 1.7f);
    m = find_material(s, "chrome");
    CHECK(m && m->type == IL_MATERIAL_MIRROR && m->specular.x == 1.0f);

    const il_light_desc *l = s->user_lights;
    CHECK(l[0].type == IL_LIGHT_POINT && l[0].intensity.z == 7.0f && l[0].position.z == 3.0f);
    CHECK(l[1].type == IL_LIGHT_SPOT && l[1].spot_angle == 25.0f && l[1].spot_exponent == 8.0f);
    CHECK_NEAR(l[1].direction.y, -1.0, 0); /* normalised */
    CHECK(l[1].intensity.y == 2.0f);
    CHECK(l[2].type == IL_LIGHT_DIRECTIONAL && l[2].direction.z == -1.0f && l[2].diameter == 2.5f);
    CHECK(l[0].diameter == 0.0f && l[1].diameter == 0.0f);

    il_camera_desc c;
    CHECK(il_scene_get_camera(s, &c));
    CHECK(c.position.z == 8.0f && c.target.y == 1.0f && c.fov_y == 35.0f);
    CHECK(s->environment.radiance.z == 0.3f);

    il_render_settings r;
    CHECK(il_scene_get_render_settings(s, &r));
    CHECK(r.width == 320 && r.height == 240 && r.spp == 32 && r.max_depth == 5 && r.seed == 7);
    CHECK(strcmp(r.method, "pt") == 0);
    CHECK(r.time_limit == 2.5);

    il_error err = {0};
    CHECK_OK(il_scene_commit(s, &err), &err);
    il_scene_release(s);
}

static void test_file_with_transform_and_overrides(void)
{
    /* McGuire's box scaled by 2, turned 90 degrees about y, moved up by 1. */
    il_scene *s = load_json_ok("cornell.json", "{\n"
        "\"materials\": {\"leftWall\": {\"type\": \"mirror\"}},\n"
        "\"meshes\": [{\"file\": \"" IL_SHARED_DIR "/scenes/cornell-box-mcguire/CornellBox-Original.obj\",\n"
        "  \"transform\": {\"translate\": [0, 1, 0], \"rotate\": [0, 1, 0, 90], \"scale\": 2}}]\n"
        "}\n");
    if (!s)
        return;
    il_scene_info info;
    il_scene_get_info(s, &info);
    CHECK(info.num_triangles == 36);
    /* Original bounds (-1.02,0,-1.04)..(1,1.99,0.99); R_y(90): (x,y,z) -> (z,y,-x). */
    CHECK_NEAR(info.bounds_min.x, 2 * -1.04, 1e-5);
    CHECK_NEAR(info.bounds_max.x, 2 * 0.99, 1e-5);
    CHECK_NEAR(info.bounds_min.y, 1.0, 1e-5);
    CHECK_NEAR(info.bounds_max.y, 1 + 2 * 1.99, 1e-5);
    CHECK_NEAR(info.bounds_min.z, 2 * -1.0, 1e-5);
    CHECK_NEAR(info.bounds_max.z, 2 * 1.02, 1e-5);
    /* The JSON material named like the file's replaces it. */
    const il_mesh *left = find_mesh(s, "leftWall");
    CHECK(left != NULL);
    if (left)
        CHECK(s->materials[left->material].type == IL_MATERIAL_MIRROR);
    /* The light quad still faces down after the rotation. */
    const il_mesh *light = find_mesh(s, "light");
    CHECK(light != NULL);
    if (light)
        CHECK_NEAR(face_normal(light, 0).y, -1.0, 1e-5);
    il_scene_release(s);

    /* A mirroring transform keeps faces facing the same way (winding reversed),
     * and "material" replaces every material of the file. */
    s = load_json_ok("mirrored.json", "{\n"
        "\"materials\": {\"grey\": {\"diffuse\": 0.5}},\n"
        "\"meshes\": [{\"file\": \"" IL_SHARED_DIR "/scenes/cornell-box-mcguire/CornellBox-Original.obj\",\n"
        "  \"transform\": {\"scale\": [1, -1, 1]}, \"material\": \"grey\"}]\n"
        "}\n");
    if (!s)
        return;
    il_scene_get_info(s, &info);
    CHECK_NEAR(info.bounds_min.y, -1.99, 1e-5);
    CHECK(info.num_emissive_triangles == 0);
    CHECK(info.num_materials == 2);
    light = find_mesh(s, "light");
    if (light)
        CHECK_NEAR(face_normal(light, 0).y, 1.0, 1e-5); /* was down, mirrored: up */
    il_scene_release(s);
}

static void test_rotations(void)
{
    /* Euler [90,0,0] and axis-angle [1,0,0,90] agree: the quad (facing +y)
     * then faces +z. */
    const char *fmt = "{\"meshes\":[{\"shape\":\"quad\",\"size\":[2,4],"
                      "\"transform\":{\"rotate\":%s}}],\"lights\":[{\"type\":\"point\"}]}";
    const char *rot[2] = {"[90,0,0]", "[1,0,0,90]"};
    for (int k = 0; k < 2; k++) {
        char json[512];
        snprintf(json, sizeof json, fmt, rot[k]);
        il_scene *s = load_json_ok("rot.json", json);
        if (!s)
            continue;
        il_scene_info info;
        il_scene_get_info(s, &info);
        CHECK_NEAR(face_normal(&s->meshes[0], 0).z, 1.0, 1e-6);
        CHECK_NEAR(info.bounds_max.x, 1.0, 1e-6);
        CHECK_NEAR(info.bounds_max.y, 2.0, 1e-6); /* z in [-2,2] became y */
        CHECK_NEAR(info.bounds_max.z, 0.0, 1e-6);
        il_scene_release(s);
    }
    /* Euler order: x first, then y, then z.  [90, 90, 0]: normal +y -> +z -> +x. */
    il_scene *s = load_json_ok("rot2.json", "{\"meshes\":[{\"shape\":\"quad\","
                               "\"transform\":{\"rotate\":[90,90,0]}}]}");
    if (s) {
        CHECK_NEAR(face_normal(&s->meshes[0], 0).x, 1.0, 1e-6);
        il_scene_release(s);
    }
}

typedef struct bad_case {
    const char *json;
    il_status status;
    const char *message;
} bad_case;

static void test_errors(void)
{
    static const bad_case cases[] = {
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"lights\":[{\"type\":\"point\"},"
         "{\"type\":\"point\",\"intensity\":\"bright\"}]}",
         IL_ERR_FORMAT, "bad.json: lights[1].intensity: expected a number or [r,g,b]"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"lights\":[{\"type\":\"laser\"}]}",
         IL_ERR_FORMAT, "bad.json: lights[0].type: expected \"point\", \"spot\" or \"directional\""},
        {"{\"meshes\":{}}", IL_ERR_FORMAT, "bad.json: meshes: expected an array"},
        {"{\"lights\":[]}", IL_ERR_FORMAT, "bad.json: meshes: missing"},
        {"[1,2]", IL_ERR_FORMAT, "bad.json: expected a JSON object"},
        {"{\"meshes\":[{\"shape\":\"quad\",\"transform\":{\"translate\":[1,2]}}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0].transform.translate: expected [x,y,z]"},
        {"{\"meshes\":[{\"shape\":\"quad\",\"transform\":{\"rotate\":[1,2]}}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0].transform.rotate: expected"},
        {"{\"meshes\":[{\"shape\":\"quad\",\"matrix\":[1,0,0]}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0].matrix: expected 16 numbers"},
        {"{\"meshes\":[{\"shape\":\"quad\",\"material\":\"nope\"}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0].material: no material named 'nope'"},
        {"{\"meshes\":[{\"shape\":\"cone\"}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0].shape: expected \"quad\", \"box\" or \"sphere\""},
        {"{\"meshes\":[{\"shape\":\"quad\",\"file\":\"a.obj\"}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0]: expected exactly one of"},
        {"{\"meshes\":[{\"positions\":[0,0,0,1,0,0,0,1,0],\"indices\":[0,1,3]}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0].indices: index out of range"},
        {"{\"meshes\":[{\"positions\":[0,0,0,1,0,0,0,1]}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0].positions: expected 3 numbers per vertex"},
        {"{\"meshes\":[{\"positions\":[0,0,0,1,0,0,0,1,\"x\"]}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0].positions: expected an array of numbers"},
        {"{\"meshes\":[{\"positions\":[0,0,0,1,0,0,2,0,0]}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0]: no triangles"},
        {"{\"materials\":{\"m\":{\"type\":\"velvet\"}},\"meshes\":[{\"shape\":\"quad\"}]}",
         IL_ERR_FORMAT, "bad.json: materials.m.type: expected \"diffuse\""},
        {"{\"materials\":{\"m\":{\"diffuse\":[1,-1,0]}},\"meshes\":[{\"shape\":\"quad\"}]}",
         IL_ERR_FORMAT, "bad.json: materials.m.diffuse: expected values >= 0"},
        {"{\"materials\":{\"m\":{\"two_sided\":1}},\"meshes\":[{\"shape\":\"quad\"}]}",
         IL_ERR_FORMAT, "bad.json: materials.m.two_sided: expected true or false"},
        {"{\"materials\":{\"m\":{\"ior\":0.5}},\"meshes\":[{\"shape\":\"quad\"}]}",
         IL_ERR_FORMAT, "bad.json: materials.m.ior: expected a number >= 1"},
        {"{\"materials\":{\"m\":{\"type\":\"thin_glass\",\"transmittance\":0.95}},"
         "\"meshes\":[{\"shape\":\"quad\"}]}",
         IL_ERR_INVALID, "bad.json: materials.m: material 'm': transmittance 0.95 is outside 0 to 0.9231"},
        {"{\"materials\":{\"m\":{\"type\":\"thin_glass\",\"specular\":[1,0.5,0.5]}},"
         "\"meshes\":[{\"shape\":\"quad\"}]}",
         IL_ERR_INVALID, "bad.json: materials.m: material 'm': a thin_glass pane is neutral"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"camera\":{\"position\":[0,0,1]}}",
         IL_ERR_FORMAT, "bad.json: camera: \"position\" and \"target\" are required"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"camera\":{\"position\":[0,0,1],\"target\":[0,0,1]}}",
         IL_ERR_INVALID, "bad.json: camera: target equals position"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"render\":{\"spp\":-4}}",
         IL_ERR_FORMAT, "bad.json: render.spp: expected a whole number"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"render\":{\"width\":2.5}}",
         IL_ERR_FORMAT, "bad.json: render.width: expected a whole number"},
        {"{\"meshes\":[{\"shape\":\"sphere\",\"radius\":0}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0].radius: expected a number > 0"},
        {"{\"meshes\":[{\"shape\":\"quad\",\"transform\":{\"scale\":0}}]}",
         IL_ERR_FORMAT, "bad.json: meshes[0].transform.scale: a scale of zero"},
        {"{\"meshes\":[{\"file\":\"missing-mesh.obj\"}]}",
         IL_ERR_IO, "missing-mesh.obj: no such file"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\n  \"lights\": [}", IL_ERR_FORMAT,
         "bad.json: invalid JSON near line 2"},
        {"", IL_ERR_FORMAT, "bad.json: invalid JSON"},
        /* Found by fuzzing: text after the object, and a key given twice
         * (cJSON reads the first), were silently ignored. */
        {"{\"meshes\":[{\"shape\":\"quad\"}]}\n{\"meshes\":[]}", IL_ERR_FORMAT,
         "bad.json: text after the scene's JSON object, near line 2, column 1"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"meshes\":[]}", IL_ERR_FORMAT,
         "bad.json: the key \"meshes\" appears twice in one object"},
        {"{\"meshes\":[{\"shape\":\"quad\",\"size\":1,\"size\":2}]}", IL_ERR_FORMAT,
         "bad.json: the key \"size\" appears twice in one object"},
        {"{\"meshes\":[{\"shape\":\"quad\",\"size\":[1,2,3]}]}", IL_ERR_FORMAT,
         "bad.json: meshes[0].size: expected a number or [sx,sz]"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"render\":{\"width\":20000}}", IL_ERR_FORMAT,
         "bad.json: render.width"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"camera\":{\"position\":[0,0,3],\"target\":[0,0,0],\"fov\":0}}",
         IL_ERR_FORMAT, "bad.json: camera.fov: expected degrees in (0, 180)"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"cloudy\"}}",
         IL_ERR_FORMAT, "bad.json: environment.sky: expected \"overcast\", \"clear\" or \"cie:1\" to \"cie:15\""},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"clear\"}}",
         IL_ERR_FORMAT, "bad.json: environment.sun: a CIE sky needs its sun"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"overcast\",\"sun\":[30,180]}}",
         IL_ERR_FORMAT, "bad.json: environment: the overcast sky has no \"sun\""},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"clear\",\"map\":\"a.hdr\"}}",
         IL_ERR_FORMAT, "bad.json: environment: \"sky\" and \"radiance\" or \"map\" exclude each other"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"radiance\":1,\"sky_lux\":5}}",
         IL_ERR_FORMAT, "bad.json: environment: \"sky_lux\", \"ground_albedo\", \"sun\", \"north\", \"sun_lux\" and \"sun_diameter\" need a \"sky\""},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"radiance\":1,\"sun_diameter\":1}}",
         IL_ERR_FORMAT, "need a \"sky\""},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"overcast\",\"sun_diameter\":1}}",
         IL_ERR_FORMAT, "bad.json: environment: the overcast sky has no \"sun\", \"north\", \"sun_lux\" or \"sun_diameter\""},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"clear\",\"sun\":[30,180],\"sun_diameter\":91}}",
         IL_ERR_FORMAT, "bad.json: environment.sun_diameter: expected a number of degrees from 0 (a point) to 90"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"clear\",\"sun\":[30,180],\"sun_diameter\":-1}}",
         IL_ERR_FORMAT, "bad.json: environment.sun_diameter: expected a number of degrees from 0 (a point) to 90"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"lights\":[{\"type\":\"point\",\"diameter\":1}]}",
         IL_ERR_FORMAT, "bad.json: lights[0].diameter: a directional light's disc: expected degrees in [0, 90]"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"lights\":[{\"type\":\"directional\",\"diameter\":95}]}",
         IL_ERR_FORMAT, "bad.json: lights[0].diameter: a directional light's disc: expected degrees in [0, 90]"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"cie:7\",\"sun\":[-3,180]}}",
         IL_ERR_FORMAT, "bad.json: environment.sun: the altitude must be above the horizon"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"clear\",\"sun\":[30]}}",
         IL_ERR_FORMAT, "bad.json: environment.sun: expected [altitude, azimuth] in degrees"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"clear\",\"sun\":{\"time\":\"2026-06-21T12:00\",\"latitude\":52,\"longitude\":13}}}",
         IL_ERR_FORMAT, "bad.json: environment.sun: expected a date, a time and its UTC offset"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"clear\",\"sun\":{\"time\":\"2026-12-21T23:00Z\",\"latitude\":52,\"longitude\":13}}}",
         IL_ERR_FORMAT, "bad.json: environment.sun: at 2026-12-21T23:00Z the sun stands"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"clear\",\"sun\":{\"time\":\"2026-06-21T12:00Z\",\"latitude\":52}}}",
         IL_ERR_FORMAT, "bad.json: environment.sun: expected \"time\", \"latitude\" and \"longitude\""},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"clear\",\"sun\":[30,180],\"sky_lux\":0}}",
         IL_ERR_FORMAT, "bad.json: environment.sky_lux: expected a number of lux > 0"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"clear\",\"sun\":[30,180],\"ground_albedo\":2}}",
         IL_ERR_FORMAT, "bad.json: environment.ground_albedo: expected a number from 0 to 1"},
        {"{\"meshes\":[{\"shape\":\"quad\"}],\"environment\":{\"sky\":\"clear\",\"sun\":[30,180],\"sun_lux\":-1}}",
         IL_ERR_FORMAT, "bad.json: environment.sun_lux: expected a number of lux >= 0"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        il_error err = {0};
        il_status st;
        il_scene *s = load_json("bad.json", cases[i].json, &st, &err);
        CHECK(s == NULL);
        CHECK(st == cases[i].status);
        if (!contains(err.message, cases[i].message)) {
            CHECK(!"error message");
            fprintf(stderr, "  case %zu: got \"%s\"\n  want \"%s\"\n", i, err.message,
                    cases[i].message);
        }
        il_scene_release(s);
    }
}

/* A key of another shape (found by fuzzing: silently ignored). */
static void check_shape_keys(void)
{
    il_scene *s = load_json_ok("shapes.json", "{\"meshes\": [{\"shape\": \"quad\", \"radius\": 2},"
                               " {\"shape\": \"sphere\", \"size\": 2}]}");
    if (!s)
        return;
    CHECK(s->num_warnings == 2);
    CHECK(any_warning_contains(s, "meshes[0]: \"radius\" and \"segments\" are a sphere's, ignored for a quad"));
    CHECK(any_warning_contains(s, "meshes[1]: \"size\" is a quad's or a box's, ignored for a sphere"));
    il_scene_release(s);
}

static void test_warnings_and_fallbacks(void)
{
    il_scene *s = load_json_ok("warn.json", "{\"colour\": 1,\n"
        "\"materials\": {\"t\": {\"texture\": \"no-such-texture.png\", \"diffuse\": [0.1, 0.2, 0.3],"
        " \"shine\": 3}},\n"
        "\"meshes\": [{\"shape\": \"quad\", \"material\": \"t\", \"colour\": 2, \"_note\": 1}],\n"
        "\"comment\": \"ignored\"}\n");
    if (!s)
        return;
    il_scene_info info;
    il_scene_get_info(s, &info);
    CHECK(info.num_warnings == 4);
    CHECK(any_warning_contains(s, "warn.json: colour: unknown key"));
    CHECK(any_warning_contains(s, "warn.json: materials.t.shine: unknown key"));
    CHECK(any_warning_contains(s, "warn.json: meshes[0].colour: unknown key"));
    CHECK(any_warning_contains(s, "no-such-texture.png"));
    const il_material *m = find_material(s, "t");
    CHECK(m && m->diffuse_texture == 0 && m->diffuse.z == 0.3f);
    CHECK(info.num_textures == 0);
    il_render_settings r;
    CHECK(!il_scene_get_render_settings(s, &r));
    CHECK(r.width == 0 && r.method[0] == '\0');

    /* No light: an error at commit (scene/lights.c), not at load. */
    il_error err = {0};
    CHECK(il_scene_commit(s, &err) == IL_ERR_INVALID);
    CHECK(err.message[0] != '\0');
    il_scene_release(s);

    /* A dielectric sheet (a quad) is warned about, as a window should be a
     * pane; a dielectric solid (a box, a sphere) is not. */
    s = load_json_ok("sheet.json", "{\"materials\": {\"g\": {\"type\": \"dielectric\"}},\n"
        "\"meshes\": [{\"shape\": \"quad\", \"material\": \"g\"}, {\"shape\": \"box\", \"material\": \"g\"},\n"
        "             {\"shape\": \"sphere\", \"material\": \"g\"}]}\n");
    if (!s)
        return;
    il_scene_get_info(s, &info);
    CHECK(info.num_warnings == 1);
    CHECK(any_warning_contains(s, "sheet.json: meshes[0]: the dielectric 'g' is on an open mesh"));
    il_scene_release(s);
}

/* The example scenes that ship in scenes/ load and commit. */
static void test_shipped_scenes(void)
{
    char root[1024];
    snprintf(root, sizeof root, "%s", __FILE__);
    char *cut = strstr(root, "tests/unit/test_load_json.c");
    if (!cut) {
        printf("skipped: the source folder is unknown (__FILE__ = %s)\n", __FILE__);
        return;
    }
    *cut = '\0';
    static const char *names[] = {"cornell-mcguire.json", "cornell-glass.json", "studio.json"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        char path[1200];
        snprintf(path, sizeof path, "%sscenes/%s", root, names[i]);
        il_error err = {0};
        il_scene *s = NULL;
        CHECK_OK(il_scene_load(path, NULL, &s, &err), &err);
        if (!s)
            continue;
        il_scene_info info;
        il_scene_get_info(s, &info);
        CHECK(info.num_warnings == 0);
        CHECK(info.has_camera);
        il_render_settings r;
        CHECK(il_scene_get_render_settings(s, &r) && r.width > 0);
        CHECK_OK(il_scene_commit(s, &err), &err);
        il_scene_release(s);
    }
}

/* "environment": {"sky": ...}: the clear sky and its sun from NREL's SPA
 * example (2003-10-17, day 290), north turned; the sun goes with its sky
 * when the environment is replaced, the scene's own lights stay; switching
 * those off (il_scene_remove_lights) keeps the sun. */
static void test_sky(void)
{
    static const char sky_json[] =
        "{\"meshes\": [{\"shape\": \"quad\"}],\n"
        " \"lights\": [{\"type\": \"point\", \"position\": [0, 1, 0]}],\n"
        " \"environment\": {\"sky\": \"clear\", \"north\": 30, \"sky_lux\": 20000,\n"
        "   \"sun\": {\"time\": \"2003-10-17T12:30:30-07:00\", \"latitude\": 39.742476,\n"
        "           \"longitude\": -105.1786}}}\n";
    il_scene *s = load_json_ok("sky.json", sky_json);
    CHECK(s->has_environment && s->envmap != NULL);
    CHECK(s->num_user_lights == 2);
    const il_light_desc *sun = &s->user_lights[1];
    CHECK(sun->type == IL_LIGHT_DIRECTIONAL);
    double alt = 0.0, az = 0.0;
    il_error err = {0};
    CHECK_OK(il_sun_position(39.742476, -105.1786, 1066419030.0, &alt, &az, &err), &err);
    CHECK_REL(sun->intensity.y, il_sun_normal_lux(12, alt, 290) / 683.0, 1e-6);
    /* Travelling away from the sun: azimuth 194.34 with north turned 30 is
     * 164.34 degrees clockwise from -z. */
    double h = alt * 3.14159265358979 / 180.0, a = (az - 30.0) * 3.14159265358979 / 180.0;
    CHECK_NEAR(sun->direction.x, -cos(h) * sin(a), 1e-5);
    CHECK_NEAR(sun->direction.y, -sin(h), 1e-5);
    CHECK_NEAR(sun->direction.z, cos(h) * cos(a), 1e-5);
    CHECK_OK(il_scene_set_environment(s, &(il_environment_desc){.radiance = {1, 1, 1}}, &err), &err);
    CHECK(s->num_user_lights == 1 && s->user_lights[0].type == IL_LIGHT_POINT);
    il_scene_release(s);
    /* The sun's disc: its own 0.533 degrees by default, "sun_diameter" in
     * degrees, 0 a point. */
    s = load_json_ok("sky.json", sky_json);
    CHECK(s->user_lights[1].diameter == 0.533f);
    il_scene_release(s);
    const double diameters[] = {2.0, 0.0};
    for (int k = 0; k < 2; k++) {
        char text[256];
        snprintf(text, sizeof text,
                 "{\"meshes\": [{\"shape\": \"quad\"}], \"environment\": {\"sky\": \"clear\", "
                 "\"sun\": [30, 180], \"sun_diameter\": %g}}", diameters[k]);
        s = load_json_ok("disc.json", text);
        CHECK(s->num_user_lights == 1 && s->user_lights[0].diameter == (float)diameters[k]);
        il_sky_desc got;
        CHECK(il_scene_get_daylight(s, &got) && got.sun_diameter == (k ? -1.0 : 2.0));
        il_scene_release(s);
    }
    /* Switching the scene's own lights off leaves the sky's sun. */
    s = load_json_ok("sky.json", sky_json);
    CHECK_OK(il_scene_remove_lights(s, &err), &err);
    CHECK(s->num_user_lights == 1 && s->user_lights[0].type == IL_LIGHT_DIRECTIONAL);
    CHECK_OK(il_scene_set_environment(s, &(il_environment_desc){.radiance = {1, 1, 1}}, &err), &err);
    CHECK(s->num_user_lights == 0);
    il_scene_release(s);

    s = load_json_ok("sky2.json", "{\"meshes\": [{\"shape\": \"quad\"}],\n"
                                  " \"environment\": {\"sky\": \"cie:3\", \"sun\": [40, 90]}}\n");
    CHECK(s->num_user_lights == 0); /* an overcast type: no direct sun */
    CHECK(s->has_environment);
    il_scene_release(s);
    s = load_json_ok("sky3.json", "{\"meshes\": [{\"shape\": \"quad\"}],\n"
                                  " \"environment\": {\"sky\": \"overcast\", \"ground_albedo\": 0}}\n");
    CHECK(s->num_user_lights == 0 && s->has_environment);
    il_scene_release(s);
}

int main(void)
{
    check_shape_keys();
    test_full_scene();
    test_file_with_transform_and_overrides();
    test_rotations();
    test_errors();
    test_warnings_and_fallbacks();
    test_shipped_scenes();
    test_sky();
    return check_report();
}
