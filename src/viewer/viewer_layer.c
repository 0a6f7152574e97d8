/* The mesh view's specular layer (radiosity, hr).  Mirror and glass
 * triangles carry no patch and no radiance in the bake; when the camera
 * rests, the worker path-traces the view (IL_METHOD_PT, the run's --spp and
 * seed) and the mesh's resolve pass takes those triangles' samples from that
 * image (viewer_mesh.c), refined pass by pass like any image.  A camera move
 * drops it until the camera rests again: the diffuse mesh itself never waits
 * for a render. */
#include <string.h>

#include "viewer/viewer_internal.h"

static bool same_camera(const orbit *a, const orbit *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

void il_view_forget_layer(viewer *v)
{
    v->layer_wanted = v->layer_ready = false;
}

void il_view_update_layer(viewer *v, double now)
{
    if (!il_view_mesh_ready(v) || !v->mesh_final || !v->mesh_specular)
        return;
    bool same = same_camera(&v->layer_cam, &v->cam);
    if (!same)
        v->layer_ready = false;
    bool resting = !v->moved && now - v->last_move >= REST_SECONDS;
    if (!resting || (v->layer_wanted && same))
        return;
    il_camera_desc c = il_view_orbit_camera(&v->cam);
    il_view_worker_request(&v->worker, &c, IL_METHOD_PT, false, false);
    pthread_mutex_lock(&v->worker.mu);
    v->layer_gen = v->worker.gen;
    pthread_mutex_unlock(&v->worker.mu);
    v->layer_wanted = true;
    v->layer_cam = v->cam;
}

void il_view_take_layer(viewer *v, uint64_t gen)
{
    if (!v->layer_wanted || gen != v->layer_gen || !v->shown.rgb ||
        !same_camera(&v->layer_cam, &v->cam))
        return;
    if (!v->layer_tex)
        glGenTextures(1, &v->layer_tex);
    glBindTexture(GL_TEXTURE_2D, v->layer_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    /* The film's radiance, rows top to bottom (the resolve pass flips y). */
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, (GLsizei)v->shown.width, (GLsizei)v->shown.height,
                 0, GL_RGB, GL_FLOAT, v->shown.rgb);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    v->layer_ready = true;
}

bool il_view_layer_done(const viewer *v, bool worker_done, uint64_t worker_gen)
{
    if (!v->mesh_specular)
        return true;
    return v->layer_ready && worker_done && worker_gen == v->layer_gen;
}
