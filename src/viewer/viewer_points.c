/* The photon map's points (key O, photon mapping and SPPM): the positions
 * of the last traced photons (the worker keeps at most every k-th, see
 * IL_VIEW_MAX_POINTS) drawn as yellow points over the image through the
 * camera, without occlusion: every stored photon shows, also behind walls. */
#include "viewer/viewer_internal.h"

void il_view_make_points(viewer *v)
{
    glGenVertexArrays(1, &v->points_vao);
    glGenBuffers(1, &v->points_vbo);
}

/* Called with the worker's mutex held (it owns the array). */
void il_view_upload_points(viewer *v, const float *xyz, size_t n)
{
    glBindVertexArray(v->points_vao);
    glBindBuffer(GL_ARRAY_BUFFER, v->points_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * 3 * sizeof *xyz), xyz, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), (void *)0);
    glBindVertexArray(0);
    v->num_points = (GLsizei)n;
}

void il_view_draw_points(viewer *v, int fw, int fh)
{
    if (!v->num_points)
        return;
    float mvp[16];
    il_view_camera_matrix(v, fh > 0 ? (float)fw / (float)fh : 1.0f, mvp);
    glUseProgram(v->mesh_prog);
    glUniformMatrix4fv(glGetUniformLocation(v->mesh_prog, "mvp"), 1, GL_TRUE, mvp);
    glUniform4f(glGetUniformLocation(v->mesh_prog, "line"), 1.0f, 0.9f, 0.1f, 1.0f);
    glPointSize(1.0f);
    glBindVertexArray(v->points_vao);
    glDrawArrays(GL_POINTS, 0, v->num_points);
    glBindVertexArray(0);
}

void il_view_free_points(viewer *v)
{
    glDeleteVertexArrays(1, &v->points_vao);
    glDeleteBuffers(1, &v->points_vbo);
}
