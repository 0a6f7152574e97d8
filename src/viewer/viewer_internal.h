/* The viewer's window state shared by its files (docs/viewer.md):
 * viewer.c runs the window, viewer_camera.c moves the camera,
 * viewer_keys.c handles keys, viewer_image.c draws the worker's image,
 * viewer_mesh.c the radiosity mesh, viewer_patches.c its patch outlines,
 * viewer_background.c the environment behind it, viewer_points.c the photon map's points,
 * viewer_save.c writes images and cameras. */
#ifndef IL_VIEWER_INTERNAL_H
#define IL_VIEWER_INTERNAL_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "viewer/viewer.h"
#include "viewer/worker.h"

/* Seconds the camera must rest before the full-resolution render starts
 * (and the mesh view draws with all its samples per pixel). */
#define REST_SECONDS 0.15
#define SPIN_SECONDS 2.0               /* the scripted orbit (key '~') lasts this long */
#define SPIN_RADIANS 0.5              /* and turns the camera this far */

typedef struct orbit {
    il_vec3 target, up;
    float distance, yaw, pitch, fov;   /* radians for the angles, degrees for fov */
} orbit;

typedef struct viewer {
    const il_viewer_options *o;
    GLFWwindow *win;
    il_view_worker worker;
    orbit cam, home;
    il_method method;
    float exposure;
    il_tonemap_op op;
    bool moved, previewing, retone, dragging;
    double last_move, drag_x, drag_y;
    il_image shown;                   /* the HDR image on screen */
    bool shown_preview;
    GLuint tex, prog, vao;
    /* Radiosity and hr: the solution as a Gouraud-shaded mesh (il_bake). */
    bool mesh_view, wireframe, has_mesh;
    bool mesh_final;                  /* the mesh is the solve's result, not a look */
    bool baking;                      /* a bake for bake_method is requested */
    il_method mesh_method, bake_method;
    uint32_t looks;                   /* looks at the running solve drawn */
    GLuint mesh_prog, mesh_vao, mesh_vbo, mesh_ibo;
    /* The mesh is drawn into an S x S supersampled float framebuffer
     * (radiance, and the debugging lines in a second layer), then averaged
     * per pixel and tone-mapped by the resolve program (viewer_mesh.c). */
    GLuint ss_fbo, ss_radiance, ss_lines, ss_depth, resolve_prog, resolve_vao;
    int ss_w, ss_h;
    GLsizei mesh_indices;
    bool normals;                     /* N: the vertex normals as lines */
    bool patch_lines;                 /* B: the patches' (hr: elements') outlines */
    GLuint patch_vao, patch_vbo;
    GLsizei patch_vertices;
    uint32_t num_patches;             /* patches of the mesh shown */
    /* The mesh view's specular layer: mirror and glass triangles (no patch)
     * show the path tracer's image of the resting camera (viewer_layer.c). */
    bool mesh_specular;               /* the mesh has triangles without a patch */
    bool layer_wanted;                /* a path-traced layer is requested for layer_cam */
    bool layer_ready;                 /* layer_tex holds it */
    uint64_t layer_gen;               /* its worker request */
    orbit layer_cam;
    GLuint layer_tex;
    /* The mesh view's background: the environment's radiance and the sun's
     * disc through each pixel (il_background_radiance), recomputed when the
     * camera or the window size changes; bg_w == 0: none (no environment). */
    GLuint bg_tex;
    int bg_w, bg_h;
    orbit bg_cam;
    bool photon_points;               /* O: photon, sppm: the photons as points */
    GLuint points_vao, points_vbo;
    GLsizei num_points;
    /* Frame rate: frames drawn per second, over the last half second or
     * more; and a scripted '~' (2 s orbiting SPIN_RADIANS at an even rate,
     * from yaw spin_yaw0, one step per frame): the frames and the preview
     * images shown per second while the camera moved. The angle follows the
     * clock, not the frame count, so where the orbit ends does not depend on
     * the machine's frame rate. */
    double fps, fps_start;
    uint32_t fps_frames;
    double spin_until, spin_start, spin_fps, spin_pps;
    float spin_yaw0;
    uint32_t spin_frames, spin_previews;
    GLuint normal_vao, normal_vbo;
    GLsizei normal_vertices;
    char title[512];                  /* the info line, also printed by scripted runs */
    char mesh_conv[64];               /* the mesh's solve: steps and unshot power */
    uint32_t rad_steps;               /* radiosity's latest step, from the worker */
    double unshot;                    /* -1: no radiosity solve running or shown */
    double radius;                    /* sppm's mean photon radius; 0: none */
} viewer;

extern const char *const il_view_op_names[4];

static inline il_vec3 v3(float x, float y, float z) { return (il_vec3){x, y, z}; }
static inline il_vec3 add(il_vec3 a, il_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline il_vec3 sub(il_vec3 a, il_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline il_vec3 scale(il_vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline float dot(il_vec3 a, il_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline il_vec3 cross(il_vec3 a, il_vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline il_vec3 normalize(il_vec3 a)
{
    float l = sqrtf(dot(a, a));
    return l > 0.0f ? scale(a, 1.0f / l) : a;
}

/* viewer.c */
bool il_view_mesh_mode(const viewer *v);   /* radiosity/hr with the mesh view on */
bool il_view_mesh_ready(const viewer *v);  /* ... and a mesh of this method to draw */
/* A new render for the camera; in the mesh view only a bake, once per
 * method: OpenGL draws the mesh from any camera. */
void il_view_request(viewer *v, bool preview);
void il_view_camera_moved(viewer *v);

/* viewer_camera.c */
orbit il_view_orbit_from(const il_camera_desc *c);
il_camera_desc il_view_orbit_camera(const orbit *o);
void il_view_camera_matrix(const viewer *v, float aspect, float out[16]);
void il_view_on_button(GLFWwindow *win, int button, int action, int mods);
void il_view_on_cursor(GLFWwindow *win, double x, double y);
void il_view_on_scroll(GLFWwindow *win, double dx, double dy);
void il_view_fly(viewer *v, double dt);

/* viewer_keys.c */
void il_view_on_key(GLFWwindow *win, int key, int scancode, int action, int mods);
void il_view_scripted_key(viewer *v, char c);

/* viewer_image.c */
GLuint il_view_compile(GLenum type, const char *src);
bool il_view_make_image_program(viewer *v);
void il_view_upload_image(viewer *v);
void il_view_draw_image(viewer *v);

/* viewer_mesh.c */
bool il_view_make_mesh_program(viewer *v);
void il_view_upload_mesh(viewer *v, const il_bake_result *b, il_method method);
void il_view_draw_mesh(viewer *v, int fw, int fh);
void il_view_free_mesh(viewer *v);

/* viewer_patches.c */
void il_view_make_patches(viewer *v);
void il_view_upload_patches(viewer *v, const il_bake_result *b);
void il_view_draw_patches(viewer *v);   /* with the mesh program bound */
void il_view_free_patches(viewer *v);

/* viewer_layer.c */
/* Requests the path-traced layer when the camera rests on a final mesh with
 * specular triangles; forgets it when the camera moved. */
void il_view_update_layer(viewer *v, double now);
/* A fresh worker image of request gen: the layer's, when it is current. */
void il_view_take_layer(viewer *v, uint64_t gen);
/* Whether the mesh view is complete: the layer too where it needs one. */
bool il_view_layer_done(const viewer *v, bool worker_done, uint64_t worker_gen);
void il_view_forget_layer(viewer *v);

/* viewer_background.c */
/* The background (environment and sun's disc) behind the mesh for the
 * current camera, at the window's size (a quarter of it while moving);
 * false: no environment. */
bool il_view_update_background(viewer *v, int fw, int fh, bool moving);
void il_view_free_background(viewer *v);

/* viewer_points.c */
void il_view_make_points(viewer *v);
void il_view_upload_points(viewer *v, const float *xyz, size_t n);
void il_view_draw_points(viewer *v, int fw, int fh);
void il_view_free_points(viewer *v);

/* viewer_save.c */
bool il_view_screenshot(viewer *v, const char *path);
void il_view_save_image(viewer *v);
void il_view_save_camera(viewer *v);

#endif
