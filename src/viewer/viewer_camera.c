/* The viewer's camera: an orbit about a target (spherical coordinates),
 * its OpenGL view-projection for the mesh view, and the mouse (drag orbits,
 * wheel dollies) and WASD/QE flying that move it (docs/viewer.md). */
#include <math.h>

#include "viewer/viewer_internal.h"

/* The orbit's spherical coordinates about +up; the up vector is kept as
 * given (orbiting assumes it is +y, as every built-in scene's is). */
orbit il_view_orbit_from(const il_camera_desc *c)
{
    orbit o = {.target = c->target, .up = c->up, .fov = c->fov_y > 0 ? c->fov_y : 40.0f};
    if (dot(o.up, o.up) == 0.0f)
        o.up = v3(0, 1, 0);
    il_vec3 d = sub(c->position, c->target);
    o.distance = sqrtf(dot(d, d));
    if (o.distance <= 0.0f)
        o.distance = 1.0f;
    o.pitch = asinf(fmaxf(-1.0f, fminf(1.0f, d.y / o.distance)));
    o.yaw = atan2f(d.x, d.z);
    return o;
}

il_camera_desc il_view_orbit_camera(const orbit *o)
{
    il_vec3 d = v3(cosf(o->pitch) * sinf(o->yaw), sinf(o->pitch), cosf(o->pitch) * cosf(o->yaw));
    return (il_camera_desc){.position = add(o->target, scale(d, o->distance)),
                            .target = o->target, .up = o->up, .fov_y = o->fov};
}

/* The camera's view-projection, row-major: the pinhole of il_camera_init
 * (src/scene/camera.c) as a look-at view and an OpenGL perspective. */
void il_view_camera_matrix(const viewer *v, float aspect, float out[16])
{
    il_camera_desc c = il_view_orbit_camera(&v->cam);
    il_vec3 f = normalize(sub(c.target, c.position));
    il_vec3 s = normalize(cross(f, c.up));
    il_vec3 u = cross(s, f);
    float view[16] = {s.x,  s.y,  s.z,  -dot(s, c.position),
                      u.x,  u.y,  u.z,  -dot(u, c.position),
                      -f.x, -f.y, -f.z, dot(f, c.position),
                      0,    0,    0,    1};
    float t = 1.0f / tanf(0.5f * c.fov_y * 3.14159265f / 180.0f);
    float n = 1e-3f * v->cam.distance, fa = 1e3f * v->cam.distance;
    float proj[16] = {t / aspect, 0, 0, 0,
                      0, t, 0, 0,
                      0, 0, (fa + n) / (n - fa), 2.0f * fa * n / (n - fa),
                      0, 0, -1, 0};
    for (int r = 0; r < 4; r++)
        for (int k = 0; k < 4; k++) {
            float acc = 0.0f;
            for (int j = 0; j < 4; j++)
                acc += proj[r * 4 + j] * view[j * 4 + k];
            out[r * 4 + k] = acc;
        }
}

void il_view_on_button(GLFWwindow *win, int button, int action, int mods)
{
    viewer *v = glfwGetWindowUserPointer(win);
    if (button != GLFW_MOUSE_BUTTON_LEFT)
        return;
    v->dragging = action == GLFW_PRESS;
    glfwGetCursorPos(win, &v->drag_x, &v->drag_y);
}

void il_view_on_cursor(GLFWwindow *win, double x, double y)
{
    viewer *v = glfwGetWindowUserPointer(win);
    if (!v->dragging)
        return;
    v->cam.yaw -= (float)(x - v->drag_x) * 0.005f;
    v->cam.pitch += (float)(y - v->drag_y) * 0.005f;
    v->cam.pitch = fmaxf(-1.55f, fminf(1.55f, v->cam.pitch));
    v->drag_x = x;
    v->drag_y = y;
    il_view_camera_moved(v);
}

void il_view_on_scroll(GLFWwindow *win, double dx, double dy)
{
    viewer *v = glfwGetWindowUserPointer(win);
    v->cam.distance *= powf(0.9f, (float)dy);
    v->cam.distance = fmaxf(1e-3f, v->cam.distance);
    il_view_camera_moved(v);
}

/* WASD flies along the view direction and sideways, Q/E down and up: the
 * target moves with the eye, at half the orbit distance per second. */
void il_view_fly(viewer *v, double dt)
{
    il_camera_desc c = il_view_orbit_camera(&v->cam);
    il_vec3 fwd = normalize(sub(c.target, c.position));
    il_vec3 right = normalize(cross(fwd, v->cam.up));
    il_vec3 up = normalize(v->cam.up);
    il_vec3 m = v3(0, 0, 0);
    if (glfwGetKey(v->win, GLFW_KEY_W) == GLFW_PRESS) m = add(m, fwd);
    if (glfwGetKey(v->win, GLFW_KEY_S) == GLFW_PRESS) m = sub(m, fwd);
    if (glfwGetKey(v->win, GLFW_KEY_D) == GLFW_PRESS) m = add(m, right);
    if (glfwGetKey(v->win, GLFW_KEY_A) == GLFW_PRESS) m = sub(m, right);
    if (glfwGetKey(v->win, GLFW_KEY_E) == GLFW_PRESS) m = add(m, up);
    if (glfwGetKey(v->win, GLFW_KEY_Q) == GLFW_PRESS) m = sub(m, up);
    if (dot(m, m) == 0.0f)
        return;
    v->cam.target = add(v->cam.target, scale(m, 0.5f * v->cam.distance * (float)dt));
    il_view_camera_moved(v);
}
