/* The built-in Cornell box ("cornell"): the measured scene of the Cornell
 * University Program of Computer Graphics, "Cornell Box Data",
 * http://www.graphics.cornell.edu/online/box/data.html, as transcribed in
 * ../shared/scenes/cornell-box-measured/ (CORNELL_BOX_DATA.md and its CSVs,
 * which say where every number was read).  Built only through the public API.
 *
 * Geometry: the published quads in millimetres, scaled by 0.001 to metres,
 * each split into triangles (v1 v2 v3) and (v1 v3 v4) in the published vertex
 * order.  Read in our right-handed y-up frame, that order is counter-clockwise
 * seen from the visible side: the walls' normals point into the box, the
 * blocks' outwards, the light's down (tests/unit/test_builtin.c checks it).
 * The published frame needs no mirroring: the camera at z = -0.8 m looks
 * along +z with up +y, so its right-hand direction is forward x up =
 * (0,0,1) x (0,1,0) = (-1,0,0) and the red wall (x ~ 0.55 m) is on the left of
 * the image, the green wall (x = 0) on the right, as the data says.
 *
 * Colours: the 76-sample reflectance spectra and the light's emission spectrum,
 * converted to linear Rec.709 through the CIE 1931 functions (core/color.h;
 * docs/builtin-scenes.md gives the formulas and the light's scale). */
#include "scene/builtin.h"

#include "core/color.h"
#include "core/vec.h"
#include "scene/loader.h"

#define CORNELL_NREFL 76
#define MM 0.001f /* published millimetres -> metres */

/* Reflectances of the white, green and red paints, 400-700 nm every 4 nm:
 * wavelength (nm), white, green, red (cornell_box_reflectance.csv). */
static const float cornell_refl[CORNELL_NREFL][4] = {
    {400.0f, 0.343f, 0.092f, 0.040f}, {404.0f, 0.445f, 0.096f, 0.046f},
    {408.0f, 0.551f, 0.098f, 0.048f}, {412.0f, 0.624f, 0.097f, 0.053f},
    {416.0f, 0.665f, 0.098f, 0.049f}, {420.0f, 0.687f, 0.095f, 0.050f},
    {424.0f, 0.708f, 0.095f, 0.053f}, {428.0f, 0.723f, 0.097f, 0.055f},
    {432.0f, 0.715f, 0.095f, 0.057f}, {436.0f, 0.710f, 0.094f, 0.056f},
    {440.0f, 0.745f, 0.097f, 0.059f}, {444.0f, 0.758f, 0.098f, 0.057f},
    {448.0f, 0.739f, 0.096f, 0.061f}, {452.0f, 0.767f, 0.101f, 0.061f},
    {456.0f, 0.777f, 0.103f, 0.060f}, {460.0f, 0.765f, 0.104f, 0.062f},
    {464.0f, 0.751f, 0.107f, 0.062f}, {468.0f, 0.745f, 0.109f, 0.062f},
    {472.0f, 0.748f, 0.112f, 0.061f}, {476.0f, 0.729f, 0.115f, 0.062f},
    {480.0f, 0.745f, 0.125f, 0.060f}, {484.0f, 0.757f, 0.140f, 0.059f},
    {488.0f, 0.753f, 0.160f, 0.057f}, {492.0f, 0.750f, 0.187f, 0.058f},
    {496.0f, 0.746f, 0.229f, 0.058f}, {500.0f, 0.747f, 0.285f, 0.058f},
    {504.0f, 0.735f, 0.343f, 0.056f}, {508.0f, 0.732f, 0.390f, 0.055f},
    {512.0f, 0.739f, 0.435f, 0.056f}, {516.0f, 0.734f, 0.464f, 0.059f},
    {520.0f, 0.725f, 0.472f, 0.057f}, {524.0f, 0.721f, 0.476f, 0.055f},
    {528.0f, 0.733f, 0.481f, 0.059f}, {532.0f, 0.725f, 0.462f, 0.059f},
    {536.0f, 0.732f, 0.447f, 0.058f}, {540.0f, 0.743f, 0.441f, 0.059f},
    {544.0f, 0.744f, 0.426f, 0.061f}, {548.0f, 0.748f, 0.406f, 0.061f},
    {552.0f, 0.728f, 0.373f, 0.063f}, {556.0f, 0.716f, 0.347f, 0.063f},
    {560.0f, 0.733f, 0.337f, 0.067f}, {564.0f, 0.726f, 0.314f, 0.068f},
    {568.0f, 0.713f, 0.285f, 0.072f}, {572.0f, 0.740f, 0.277f, 0.080f},
    {576.0f, 0.754f, 0.266f, 0.090f}, {580.0f, 0.764f, 0.250f, 0.099f},
    {584.0f, 0.752f, 0.230f, 0.124f}, {588.0f, 0.736f, 0.207f, 0.154f},
    {592.0f, 0.734f, 0.186f, 0.192f}, {596.0f, 0.741f, 0.171f, 0.255f},
    {600.0f, 0.740f, 0.160f, 0.287f}, {604.0f, 0.732f, 0.148f, 0.349f},
    {608.0f, 0.745f, 0.141f, 0.402f}, {612.0f, 0.755f, 0.136f, 0.443f},
    {616.0f, 0.751f, 0.130f, 0.487f}, {620.0f, 0.744f, 0.126f, 0.513f},
    {624.0f, 0.731f, 0.123f, 0.558f}, {628.0f, 0.733f, 0.121f, 0.584f},
    {632.0f, 0.744f, 0.122f, 0.620f}, {636.0f, 0.731f, 0.119f, 0.606f},
    {640.0f, 0.712f, 0.114f, 0.609f}, {644.0f, 0.708f, 0.115f, 0.651f},
    {648.0f, 0.729f, 0.117f, 0.612f}, {652.0f, 0.730f, 0.117f, 0.610f},
    {656.0f, 0.727f, 0.118f, 0.650f}, {660.0f, 0.707f, 0.120f, 0.638f},
    {664.0f, 0.703f, 0.122f, 0.627f}, {668.0f, 0.729f, 0.128f, 0.620f},
    {672.0f, 0.750f, 0.132f, 0.630f}, {676.0f, 0.760f, 0.139f, 0.628f},
    {680.0f, 0.751f, 0.144f, 0.642f}, {684.0f, 0.739f, 0.146f, 0.639f},
    {688.0f, 0.724f, 0.150f, 0.657f}, {692.0f, 0.730f, 0.152f, 0.639f},
    {696.0f, 0.740f, 0.157f, 0.635f}, {700.0f, 0.737f, 0.159f, 0.642f},
};

/* The light's emission spectrum (cornell_box_light_emission.csv): piecewise
 * linear, zero outside 400-700 nm. */
static const float cornell_light_lambda[4] = {400.0f, 500.0f, 600.0f, 700.0f};
static const float cornell_light_value[4] = {0.0f, 8.0f, 15.6f, 18.4f};

/* The published light lies in the ceiling plane (y = 548.8 mm).  It is
 * lowered by 0.1 mm to y = 548.7 so that it does not z-fight with the
 * ceiling; 0.1 mm is far above the ray offsets (about 1e-5 of the scene) and
 * far below anything visible. */
#define CORNELL_LIGHT_Y 548.7f

typedef struct cornell_quad {
    float v[4][3]; /* millimetres, published order */
} cornell_quad;

/* Floor, ceiling, back wall (white), right wall (green, x = 0), left wall (red). */
static const cornell_quad cornell_walls[5] = {
    {{{552.8f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 559.2f}, {549.6f, 0.0f, 559.2f}}},
    {{{556.0f, 548.8f, 0.0f}, {556.0f, 548.8f, 559.2f}, {0.0f, 548.8f, 559.2f}, {0.0f, 548.8f, 0.0f}}},
    {{{549.6f, 0.0f, 559.2f}, {0.0f, 0.0f, 559.2f}, {0.0f, 548.8f, 559.2f}, {556.0f, 548.8f, 559.2f}}},
    {{{0.0f, 0.0f, 559.2f}, {0.0f, 0.0f, 0.0f}, {0.0f, 548.8f, 0.0f}, {0.0f, 548.8f, 559.2f}}},
    {{{552.8f, 0.0f, 0.0f}, {549.6f, 0.0f, 559.2f}, {556.0f, 548.8f, 559.2f}, {556.0f, 548.8f, 0.0f}}},
};
static const char *const cornell_wall_names[5] = {"floor", "ceiling", "back_wall", "right_wall_green",
                                                  "left_wall_red"};

/* Short block: top and four sides. */
static const cornell_quad cornell_short_block[5] = {
    {{{130.0f, 165.0f, 65.0f}, {82.0f, 165.0f, 225.0f}, {240.0f, 165.0f, 272.0f}, {290.0f, 165.0f, 114.0f}}},
    {{{290.0f, 0.0f, 114.0f}, {290.0f, 165.0f, 114.0f}, {240.0f, 165.0f, 272.0f}, {240.0f, 0.0f, 272.0f}}},
    {{{130.0f, 0.0f, 65.0f}, {130.0f, 165.0f, 65.0f}, {290.0f, 165.0f, 114.0f}, {290.0f, 0.0f, 114.0f}}},
    {{{82.0f, 0.0f, 225.0f}, {82.0f, 165.0f, 225.0f}, {130.0f, 165.0f, 65.0f}, {130.0f, 0.0f, 65.0f}}},
    {{{240.0f, 0.0f, 272.0f}, {240.0f, 165.0f, 272.0f}, {82.0f, 165.0f, 225.0f}, {82.0f, 0.0f, 225.0f}}},
};

/* Tall block: top and four sides. */
static const cornell_quad cornell_tall_block[5] = {
    {{{423.0f, 330.0f, 247.0f}, {265.0f, 330.0f, 296.0f}, {314.0f, 330.0f, 456.0f}, {472.0f, 330.0f, 406.0f}}},
    {{{423.0f, 0.0f, 247.0f}, {423.0f, 330.0f, 247.0f}, {472.0f, 330.0f, 406.0f}, {472.0f, 0.0f, 406.0f}}},
    {{{472.0f, 0.0f, 406.0f}, {472.0f, 330.0f, 406.0f}, {314.0f, 330.0f, 456.0f}, {314.0f, 0.0f, 456.0f}}},
    {{{314.0f, 0.0f, 456.0f}, {314.0f, 330.0f, 456.0f}, {265.0f, 330.0f, 296.0f}, {265.0f, 0.0f, 296.0f}}},
    {{{265.0f, 0.0f, 296.0f}, {265.0f, 330.0f, 296.0f}, {423.0f, 330.0f, 247.0f}, {423.0f, 0.0f, 247.0f}}},
};

static const cornell_quad cornell_light = {{{343.0f, CORNELL_LIGHT_Y, 227.0f},
                                            {343.0f, CORNELL_LIGHT_Y, 332.0f},
                                            {213.0f, CORNELL_LIGHT_Y, 332.0f},
                                            {213.0f, CORNELL_LIGHT_Y, 227.0f}}};

/* Adds `n` quads as one mesh: 4 vertices and 2 triangles per quad, in metres. */
static il_status add_quads(il_scene *scene, const char *name, const cornell_quad *quads, int n,
                           uint32_t material, il_error *err)
{
    float pos[5 * 4 * 3];
    uint32_t idx[5 * 2 * 3];
    for (int q = 0; q < n; q++) {
        for (int v = 0; v < 4; v++)
            for (int k = 0; k < 3; k++)
                pos[(q * 4 + v) * 3 + k] = quads[q].v[v][k] * MM;
        uint32_t b = (uint32_t)q * 4;
        const uint32_t tri[6] = {b, b + 1, b + 2, b, b + 2, b + 3};
        for (int k = 0; k < 6; k++)
            idx[q * 6 + k] = tri[k];
    }
    il_mesh_desc md = {
        .name = name,
        .num_vertices = (uint32_t)n * 4,
        .num_triangles = (uint32_t)n * 2,
        .positions = pos,
        .indices = idx,
        .material = material,
    };
    return il_scene_add_mesh(scene, &md, err);
}

/* Albedo of reflectance column `col` (1 white, 2 green, 3 red). */
static il_vec3 cornell_albedo(int col)
{
    float lambda[CORNELL_NREFL], value[CORNELL_NREFL];
    for (int i = 0; i < CORNELL_NREFL; i++) {
        lambda[i] = cornell_refl[i][0];
        value[i] = cornell_refl[i][col];
    }
    return il_reflectance_to_rgb(lambda, value, CORNELL_NREFL);
}

/* The materials and the walls, shared by both boxes: *white and *light are
 * the white paint's and the lamp's materials.  add_light adds the lamp and
 * the camera after the box's contents (the mesh order of the original box). */
static il_status add_shell(il_scene *scene, uint32_t *white_out, uint32_t *light_out, il_error *err)
{
    il_status st;
    uint32_t white, green, red, light;
    il_material_desc m = {.name = "white", .type = IL_MATERIAL_DIFFUSE, .diffuse = cornell_albedo(1)};
    if ((st = il_scene_add_material(scene, &m, &white, err)) != IL_OK)
        return st;
    m = (il_material_desc){.name = "green", .type = IL_MATERIAL_DIFFUSE, .diffuse = cornell_albedo(2)};
    if ((st = il_scene_add_material(scene, &m, &green, err)) != IL_OK)
        return st;
    m = (il_material_desc){.name = "red", .type = IL_MATERIAL_DIFFUSE, .diffuse = cornell_albedo(3)};
    if ((st = il_scene_add_material(scene, &m, &red, err)) != IL_OK)
        return st;
    /* The data gives no reflectance for the light's diffuser: the white paint's. */
    m = (il_material_desc){
        .name = "light",
        .type = IL_MATERIAL_DIFFUSE,
        .diffuse = cornell_albedo(1),
        .emission = il_emission_to_rgb(cornell_light_lambda, cornell_light_value, 4),
    };
    if ((st = il_scene_add_material(scene, &m, &light, err)) != IL_OK)
        return st;

    const uint32_t wall_material[5] = {white, white, white, green, red};
    for (int i = 0; i < 5; i++)
        if ((st = add_quads(scene, cornell_wall_names[i], &cornell_walls[i], 1, wall_material[i], err)) !=
            IL_OK)
            return st;
    *white_out = white;
    *light_out = light;
    return IL_OK;
}

static il_status add_light(il_scene *scene, uint32_t light, il_error *err)
{
    il_status st = add_quads(scene, "light", &cornell_light, 1, light, err);
    if (st != IL_OK)
        return st;
    /* Published camera: at (278, 273, -800) mm looking along +z, up +y, a
     * 35 mm lens on a 25 x 25 mm film: fov = 2 atan(12.5 / 35) = 39.3076 deg. */
    il_camera_desc cam = {
        .position = {278.0f * MM, 273.0f * MM, -800.0f * MM},
        .target = {278.0f * MM, 273.0f * MM, 0.0f},
        .up = {0.0f, 1.0f, 0.0f},
        .fov_y = (float)(2.0 * atan(12.5 / 35.0) * 180.0 / 3.14159265358979323846),
    };
    return il_scene_set_camera(scene, &cam, err);
}

il_status il_builtin_cornell(il_scene *scene, il_error *err)
{
    uint32_t white, light;
    il_status st = add_shell(scene, &white, &light, err);
    if (st == IL_OK)
        st = add_quads(scene, "short_block", cornell_short_block, 5, white, err);
    if (st == IL_OK)
        st = add_quads(scene, "tall_block", cornell_tall_block, 5, white, err);
    return st == IL_OK ? add_light(scene, light, err) : st;
}

/* A sphere of radius r (mm) resting on the floor at (x, z) mm. */
static il_status add_sphere(il_scene *scene, const char *name, float x, float z, float r,
                            uint32_t material, il_error *err)
{
    il_shape_mesh sm;
    il_status st = il_shape_sphere(r * MM, 96, &sm, err);
    if (st != IL_OK)
        return st;
    for (uint32_t v = 0; v < sm.num_vertices; v++) {
        sm.positions[v * 3 + 0] += x * MM;
        sm.positions[v * 3 + 1] += r * MM;
        sm.positions[v * 3 + 2] += z * MM;
    }
    il_mesh_desc md = {.name = name,
                       .num_vertices = sm.num_vertices,
                       .num_triangles = sm.num_triangles,
                       .positions = sm.positions,
                       .normals = sm.normals,
                       .indices = sm.indices,
                       .material = material};
    st = il_scene_add_mesh(scene, &md, err);
    il_shape_free(&sm);
    return st;
}

il_status il_builtin_cornell_spheres(il_scene *scene, il_error *err)
{
    uint32_t white, light, mirror, glass;
    il_status st = add_shell(scene, &white, &light, err);
    il_material_desc m = {.name = "mirror", .type = IL_MATERIAL_MIRROR};
    if (st == IL_OK)
        st = il_scene_add_material(scene, &m, &mirror, err);
    m = (il_material_desc){.name = "glass", .type = IL_MATERIAL_DIELECTRIC, .ior = 1.5f};
    if (st == IL_OK)
        st = il_scene_add_material(scene, &m, &glass, err);
    /* Jensen's arrangement (2001, fig. 9.4): the mirror ball at the back
     * left, the glass ball in front on the right, under the light's edge. */
    if (st == IL_OK)
        st = add_sphere(scene, "mirror_sphere", 185.0f, 370.0f, 100.0f, mirror, err);
    if (st == IL_OK)
        st = add_sphere(scene, "glass_sphere", 380.0f, 180.0f, 100.0f, glass, err);
    return st == IL_OK ? add_light(scene, light, err) : st;
}
