/* The viewer's keys (docs/viewer.md lists them) and the scripted runs'
 * --keys, which press them one by one. */
#include <math.h>

#include "viewer/viewer_internal.h"

static const il_method method_cycle[] = {IL_METHOD_PT,        IL_METHOD_SPPM, IL_METHOD_PHOTON,
                                         IL_METHOD_RADIOSITY, IL_METHOD_HR,   IL_METHOD_RSM,
                                         IL_METHOD_LINESPACE, IL_METHOD_IBL};

void il_view_on_key(GLFWwindow *win, int key, int scancode, int action, int mods)
{
    viewer *v = glfwGetWindowUserPointer(win);
    if (action != GLFW_PRESS && action != GLFW_REPEAT)
        return;
    switch (key) {
    case GLFW_KEY_ESCAPE:
        glfwSetWindowShouldClose(win, GLFW_TRUE);
        break;
    case GLFW_KEY_R:                  /* camera back to the start, accumulation restarts */
        v->cam = v->home;
        il_view_camera_moved(v);
        break;
    case GLFW_KEY_SPACE:              /* restart the accumulation */
        il_view_request(v, false);
        break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
        v->exposure += 0.5f;
        v->retone = true;
        break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
        v->exposure -= 0.5f;
        v->retone = true;
        break;
    case GLFW_KEY_T:
        v->op = (il_tonemap_op)((v->op + 1) % 4);
        v->retone = true;
        break;
    case GLFW_KEY_LEFT_BRACKET:
        v->cam.fov = fmaxf(5.0f, v->cam.fov - 5.0f);
        il_view_camera_moved(v);
        break;
    case GLFW_KEY_RIGHT_BRACKET:
        v->cam.fov = fminf(150.0f, v->cam.fov + 5.0f);
        il_view_camera_moved(v);
        break;
    case GLFW_KEY_M: {
        size_t n = sizeof method_cycle / sizeof method_cycle[0], k = 0;
        while (k < n && method_cycle[k] != v->method)
            k++;
        v->method = method_cycle[(k + 1) % n];
        il_view_request(v, false);
        break;
    }
    case GLFW_KEY_V:                  /* radiosity, hr: mesh or path-traced image */
        v->mesh_view = !v->mesh_view;
        il_view_request(v, false);
        break;
    case GLFW_KEY_L:                  /* mesh view: triangle (patch) edges */
        v->wireframe = !v->wireframe;
        break;
    case GLFW_KEY_B:                  /* mesh view: patch (hr: element) boundaries */
        v->patch_lines = !v->patch_lines;
        break;
    case GLFW_KEY_N:                  /* mesh view: vertex normals */
        v->normals = !v->normals;
        break;
    case GLFW_KEY_O:                  /* photon, sppm: the photon map's points */
        v->photon_points = !v->photon_points;
        break;
    case GLFW_KEY_F9:
    case GLFW_KEY_P:
        il_view_save_image(v);
        break;
    case GLFW_KEY_C:
        il_view_save_camera(v);
        break;
    default:
        break;
    }
}

/* Scripted mode's key: as if pressed, or an orbit step for '<' and '>'. */
void il_view_scripted_key(viewer *v, char c)
{
    if (c == '~') {                   /* orbit for 2 s, measuring the frame rate */
        v->spin_start = glfwGetTime();
        v->spin_until = v->spin_start + SPIN_SECONDS;
        v->spin_yaw0 = v->cam.yaw;
        v->spin_frames = v->spin_previews = 0;
        return;
    }
    if (c == '<' || c == '>') {
        v->cam.yaw += c == '<' ? -0.3f : 0.3f;
        il_view_camera_moved(v);
        return;
    }
    int key = c == '+' ? GLFW_KEY_EQUAL : c == '-' ? GLFW_KEY_MINUS
            : c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c;
    il_view_on_key(v->win, key, 0, GLFW_PRESS, 0);
}
