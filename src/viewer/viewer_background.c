/* The mesh view's background: the environment (`--env`, or the scene's
 * sky) and the sun's disc where no triangle covers a sample, as `illum
 * render` shows them where a camera ray escapes.  Computed on the CPU (viewer_env.c) into a float
 * texture that the mesh's resolve pass reads (viewer_mesh.c); a quarter of
 * the size while the camera moves. */
#include <stdlib.h>
#include <string.h>

#include "viewer/viewer_env.h"
#include "viewer/viewer_internal.h"

bool il_view_update_background(viewer *v, int fw, int fh, bool moving)
{
    if (!il_view_has_environment(v->o->scene) || fw <= 0 || fh <= 0)
        return false;
    int w = moving ? (fw + 3) / 4 : fw, h = moving ? (fh + 3) / 4 : fh;
    if (v->bg_w == w && v->bg_h == h && memcmp(&v->bg_cam, &v->cam, sizeof v->cam) == 0)
        return true;
    il_camera_desc desc = il_view_orbit_camera(&v->cam);
    float *rgb = il_view_environment_pixels(v->o->scene, &desc, w, h);
    if (!rgb)
        return v->bg_w > 0;           /* keep the last one */
    if (!v->bg_tex)
        glGenTextures(1, &v->bg_tex);
    glBindTexture(GL_TEXTURE_2D, v->bg_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    /* Rows top to bottom: texture row 0 is the image's top (the resolve
     * pass flips y). */
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, w, h, 0, GL_RGB, GL_FLOAT, rgb);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    free(rgb);
    v->bg_w = w;
    v->bg_h = h;
    v->bg_cam = v->cam;
    return true;
}

void il_view_free_background(viewer *v)
{
    if (v->bg_tex)
        glDeleteTextures(1, &v->bg_tex);
    v->bg_tex = 0;
    v->bg_w = v->bg_h = 0;
}
