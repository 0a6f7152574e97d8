/* The viewer's files: the image shown (EXR and PNG), the window's pixels
 * (screenshots) and the camera as JSON for `illum render --camera-file`. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"
#include "viewer/viewer_internal.h"

/* The image shown as EXR and PNG; in the mesh view only the window's
 * pixels as PNG (there is no radiance image to save). */
void il_view_save_image(viewer *v)
{
    char path[1024];
    if (il_view_mesh_ready(v)) {
        snprintf(path, sizeof path, "%s.png", v->o->save_prefix);
        if (il_view_screenshot(v, path) && !v->o->quiet)
            fprintf(stderr, "illum: view: wrote %s\n", path);
        return;
    }
    if (!v->shown.rgb)
        return;
    il_error err = {0};
    il_tonemap_desc tm = {.op = v->op, .exposure = v->exposure};
    il_write_desc wd = {.tonemap = &tm, .exr_precision = IL_EXR_FLOAT};
    const char *ext[] = {".exr", ".png"};
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s%s", v->o->save_prefix, ext[k]);
        if (il_image_write(&v->shown, path, &wd, &err) != IL_OK)
            cli_error("%s", err.message);
        else if (!v->o->quiet)
            fprintf(stderr, "illum: view: wrote %s\n", path);
    }
}

void il_view_save_camera(viewer *v)
{
    il_camera_desc c = il_view_orbit_camera(&v->cam);
    cJSON *j = cJSON_CreateObject();
    float p[3] = {c.position.x, c.position.y, c.position.z};
    float t[3] = {c.target.x, c.target.y, c.target.z};
    float u[3] = {c.up.x, c.up.y, c.up.z};
    cJSON_AddItemToObject(j, "position", cJSON_CreateFloatArray(p, 3));
    cJSON_AddItemToObject(j, "target", cJSON_CreateFloatArray(t, 3));
    cJSON_AddItemToObject(j, "up", cJSON_CreateFloatArray(u, 3));
    cJSON_AddNumberToObject(j, "fov", c.fov_y);
    char path[1024];
    snprintf(path, sizeof path, "%s-camera.json", v->o->save_prefix);
    if (cli_write_json(path, j) && !v->o->quiet)
        fprintf(stderr, "illum: view: wrote %s\n", path);
    cJSON_Delete(j);
}

/* The framebuffer as a PNG: 8-bit display values back to linear, so the
 * PNG writer's sRGB transfer gives the same bytes. */
bool il_view_screenshot(viewer *v, const char *path)
{
    int w, h;
    glfwGetFramebufferSize(v->win, &w, &h);
    unsigned char *px = malloc((size_t)w * h * 3);
    il_image img = {0};
    il_error err = {0};
    if (!px || il_image_alloc(&img, (uint32_t)w, (uint32_t)h, &err) != IL_OK) {
        free(px);
        cli_error("view: out of memory for the screenshot");
        return false;
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, px);
    float lut[256];
    for (int i = 0; i < 256; i++) {   /* IEC 61966-2-1 sRGB decoding */
        float c = (float)i / 255.0f;
        lut[i] = c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
    }
    for (int y = 0; y < h; y++)       /* GL rows run bottom to top */
        for (int x = 0; x < w * 3; x++)
            img.rgb[(size_t)y * w * 3 + x] = lut[px[(size_t)(h - 1 - y) * w * 3 + x]];
    free(px);
    il_status st = il_image_write(&img, path, NULL, &err);
    il_image_free(&img);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        return false;
    }
    return true;
}
