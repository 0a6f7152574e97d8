/* The viewer's render thread: runs il_render for the latest camera and
 * hands every complete film to the window (docs/viewer.md). */
#ifndef IL_VIEWER_WORKER_H
#define IL_VIEWER_WORKER_H

#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include "illum/illum.h"

/* The most photon points handed to the window (every k-th photon beyond). */
#define IL_VIEW_MAX_POINTS 20000u

typedef struct il_view_worker {
    pthread_t thread;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    il_scene *scene;               /* only the worker touches it while running */
    il_render_desc base;           /* the command line's settings */
    uint32_t width, height;
    /* Request, written by the window under mu. */
    uint64_t gen;                  /* bumped by every request */
    il_camera_desc cam;
    il_method method;
    bool preview;                  /* quarter resolution, 1 spp, path tracing */
    bool bake;                     /* radiosity/hr: il_bake's per-vertex meshes
                                      instead of an image (camera-independent) */
    bool quit;
    /* Result, written by the worker under mu. */
    uint64_t run_gen;              /* the request being rendered */
    il_image image;                /* latest complete film, resolved */
    bool fresh;                    /* image not yet taken by the window */
    bool image_preview;
    uint64_t image_gen;            /* the request the image was rendered for */
    uint32_t passes;
    double seconds;
    uint64_t rays;
    il_bake_result *baked;         /* a bake (final or a look at the solve so far)
                                      not yet taken by the window */
    il_method baked_method;
    bool baked_final;              /* baked is the solve's result, not a look */
    double last_look;              /* seconds (worker clock) of the last look published */
    bool sync_looks;               /* scripted: every look, each waiting until the
                                      window took it (set before the start) */
    uint32_t rad_steps;            /* radiosity: shots (or sweeps) of the last solve */
    double unshot;                 /* radiosity: unshot / initial power; -1: none */
    double radius;                 /* sppm: the mean photon radius after the last
                                      pass (il_render_progress.radius); 0: none */
    float *points;                 /* photon, sppm: the last traced photons' positions
                                      (3 floats each, at most 2 IL_VIEW_MAX_POINTS);
                                      the window copies them when points_fresh */
    size_t num_points;
    bool points_fresh;
    bool done;                     /* the request's render finished */
    bool failed;
    char message[512];
} il_view_worker;

/* Starts the thread; w->scene, base, width, height, cam and method must be set. */
bool il_view_worker_start(il_view_worker *w);
/* Asks for a new render (restarting accumulation). */
void il_view_worker_request(il_view_worker *w, const il_camera_desc *cam, il_method method,
                            bool preview, bool bake);
/* Stops the render and joins the thread. */
void il_view_worker_stop(il_view_worker *w);

#endif
