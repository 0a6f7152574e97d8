/* The pinhole camera: centre ray, field-of-view edges, handedness. */
#include "check.h"
#include "scene/camera.h"

static float angle_deg(il_vec3 a, il_vec3 b)
{
    float c = v3_dot(v3_normalize(a), v3_normalize(b));
    return acosf(il_clampf(c, -1.0f, 1.0f)) * 180.0f / IL_PI;
}

int main(void)
{
    /* An arbitrary camera: the centre of the image looks at the target. */
    {
        il_camera_desc d = {.position = {1, 2, 3}, .target = {4, 2, -1}, .up = {0, 1, 0}, .fov_y = 50};
        il_camera cam;
        il_camera_init(&cam, &d, 64, 32);
        il_vec3 c = il_camera_ray_dir(&cam, 32.0f, 16.0f);
        il_vec3 expect = v3_normalize(v3(3, 0, -4));
        CHECK_NEAR(c.x, expect.x, 1e-6);
        CHECK_NEAR(c.y, expect.y, 1e-6);
        CHECK_NEAR(c.z, expect.z, 1e-6);
        CHECK_NEAR(v3_length(c), 1.0, 1e-6);
        /* Top and bottom edges are fov/2 from the axis, above and below. */
        il_vec3 top = il_camera_ray_dir(&cam, 32.0f, 0.0f);
        il_vec3 bottom = il_camera_ray_dir(&cam, 32.0f, 32.0f);
        CHECK_NEAR(angle_deg(top, expect), 25.0, 1e-3);
        CHECK_NEAR(angle_deg(bottom, expect), 25.0, 1e-3);
        CHECK(top.y > 0.0f && bottom.y < 0.0f);
        /* Left/right edges: atan(tan(fov/2) * aspect), aspect = 64/32 = 2. */
        float half_x = atanf(tanf(25.0f * IL_PI / 180.0f) * 2.0f) * 180.0f / IL_PI;
        il_vec3 right = il_camera_ray_dir(&cam, 64.0f, 16.0f);
        il_vec3 left = il_camera_ray_dir(&cam, 0.0f, 16.0f);
        CHECK_NEAR(angle_deg(right, expect), half_x, 1e-3);
        CHECK_NEAR(angle_deg(left, expect), half_x, 1e-3);
        /* Right is cross(forward, up) = cross((3,0,-4)/5, (0,1,0)) = (4,0,3)/5. */
        il_vec3 r = v3(0.8f, 0.0f, 0.6f);
        CHECK(v3_dot(v3_sub(right, expect), r) > 0.0f);
        CHECK(v3_dot(v3_sub(left, expect), r) < 0.0f);
        CHECK_NEAR(right.y, 0.0, 1e-6);
    }

    /* The standard view: from +z looking down -z, image x is world +x and
     * image y (rows downwards) is world -y: right-handed, y up. */
    {
        il_camera_desc d = {.position = {0, 0, 5}, .target = {0, 0, 0}}; /* zero up and fov: defaults */
        il_camera cam;
        il_camera_init(&cam, &d, 100, 100);
        il_vec3 tr = il_camera_ray_dir(&cam, 100.0f, 0.0f); /* top-right corner */
        CHECK(tr.x > 0.0f && tr.y > 0.0f && tr.z < 0.0f);
        il_vec3 top = il_camera_ray_dir(&cam, 50.0f, 0.0f);
        CHECK_NEAR(angle_deg(top, v3(0, 0, -1)), 20.0, 1e-3); /* default fov 40 */
        /* Pixel centres are symmetric about the axis. */
        il_vec3 a = il_camera_ray_dir(&cam, 0.5f, 50.0f), b = il_camera_ray_dir(&cam, 99.5f, 50.0f);
        CHECK_NEAR(a.x, -b.x, 1e-6);
        CHECK_NEAR(a.z, b.z, 1e-6);
        /* A point on the image plane at distance 1 maps linearly to pixels:
         * x = tan(fov/2) * (2 fx / W - 1). */
        il_vec3 q = il_camera_ray_dir(&cam, 75.0f, 50.0f);
        CHECK_NEAR(q.x / -q.z, 0.5 * tan(20.0 * 3.14159265358979 / 180.0), 1e-6);
    }

    /* Looking straight down with up = -z: image x is +x, image rows grow to +z. */
    {
        il_camera_desc d = {.position = {0, 4, 0}, .target = {0, 0, 0}, .up = {0, 0, -1}, .fov_y = 30};
        il_camera cam;
        il_camera_init(&cam, &d, 10, 10);
        il_vec3 p = il_camera_ray_dir(&cam, 10.0f, 10.0f); /* bottom-right */
        CHECK(p.x > 0.0f && p.z > 0.0f && p.y < 0.0f);
    }
    return check_report();
}
