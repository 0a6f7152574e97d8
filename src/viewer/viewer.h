/* The interactive viewer behind `illum view` (docs/viewer.md): a GLFW window
 * with an OpenGL 3.3 core context showing a method's progressive image,
 * rendered by il_render on a worker thread.  Built only with IL_VIEWER. */
#ifndef IL_VIEWER_VIEWER_H
#define IL_VIEWER_VIEWER_H

#include <stdbool.h>
#include <stdint.h>
#include "illum/illum.h"

typedef struct il_viewer_options {
    il_scene *scene;                 /* committed, with its camera set */
    const char *scene_name;          /* for the window title */
    il_render_desc desc;             /* method, spp (0: refine without end), depth, seed */
    uint32_t width, height;          /* image and window size */
    float exposure;                  /* EV */
    il_tonemap_op op;
    uint32_t frames;                 /* scripted: > 0 exits after this many frames
                                        once the image is complete */
    const char *screenshot;          /* scripted: the framebuffer as PNG at exit */
    const char *look_screenshot;     /* scripted: the framebuffer as PNG when the first
                                        look at a radiosity/hr solve is drawn */
    const char *keys;                /* scripted: keys pressed one per frame once the
                                        image is complete, each waiting for the
                                        render it restarts: letters, '+', '-', and
                                        '<' '>' to orbit 0.3 rad left/right */
    const char *save_prefix;         /* F9/P, C: PREFIX.exr/.png, PREFIX-camera.json */
    bool quiet;
} il_viewer_options;

/* Runs the window until it is closed (or the scripted frames are shown).
 * Returns an IL_EXIT_* status; prints its own errors. */
int il_viewer_run(const il_viewer_options *o);

#endif
