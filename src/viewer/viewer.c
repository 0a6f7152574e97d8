/* The viewer's window: GLFW + OpenGL 3.3 core (libepoxy loads it).  The
 * worker's latest image is tone-mapped on the CPU with il_tonemap (the same
 * curves as `illum render` PNGs) and drawn as a texture by a fullscreen
 * triangle; the camera orbits, dollies and flies, and every move restarts
 * the accumulation with a low-resolution preview (docs/viewer.md).  This
 * file runs the window and its loop; viewer_internal.h lists the others. */
#include "viewer/viewer_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "cli/cli.h"


const char *const il_view_op_names[4] = {"linear", "gamma", "reinhard", "filmic"};

bool il_view_mesh_mode(const viewer *v)
{
    return v->mesh_view && (v->method == IL_METHOD_RADIOSITY || v->method == IL_METHOD_HR);
}

bool il_view_mesh_ready(const viewer *v)
{
    return il_view_mesh_mode(v) && v->has_mesh && v->mesh_method == v->method;
}

void il_view_request(viewer *v, bool preview)
{
    il_camera_desc c = il_view_orbit_camera(&v->cam);
    v->previewing = false;
    if (il_view_mesh_mode(v)) {
        bool have = v->has_mesh && v->mesh_final && v->mesh_method == v->method;
        if (!have && !(v->baking && v->bake_method == v->method)) {
            il_view_forget_layer(v);
            il_view_worker_request(&v->worker, &c, v->method, false, true);
            v->looks = 0;
            v->baking = true;
            v->bake_method = v->method;
        }
        return;
    }
    v->baking = false;
    il_view_forget_layer(v);
    il_view_worker_request(&v->worker, &c, v->method, preview, false);
    v->previewing = preview;
}

void il_view_camera_moved(viewer *v)
{
    v->moved = true;
    v->last_move = glfwGetTime();
}

static void draw(viewer *v)
{
    int fw, fh;
    glfwGetFramebufferSize(v->win, &fw, &fh);
    glViewport(0, 0, fw, fh);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    if (il_view_mesh_ready(v))
        il_view_draw_mesh(v, fw, fh);
    else if (v->shown.rgb && !il_view_mesh_mode(v))
        il_view_draw_image(v);
    if (v->photon_points && (v->method == IL_METHOD_PHOTON || v->method == IL_METHOD_SPPM))
        il_view_draw_points(v, fw, fh);
}

static void update_title(viewer *v, uint32_t passes, double secs, uint64_t rays, bool done,
                         bool failed)
{
    char t[512], conv[64] = "", patches[64] = "", layer[64] = "";
    if (v->unshot >= 0.0)             /* the radiosity solve's convergence */
        snprintf(conv, sizeof conv, " - step %u, unshot %.3g%%", v->rad_steps,
                 100.0 * v->unshot);
    else if (v->method == IL_METHOD_SPPM && v->radius > 0.0 && !v->shown_preview)
        snprintf(conv, sizeof conv, " - radius %.3g m", v->radius);   /* SPPM's */
    if (v->mesh_specular && v->layer_ready)   /* the path-traced mirror and glass */
        snprintf(layer, sizeof layer, " - specular layer %u spp", passes);
    if (v->patch_lines)
        snprintf(patches, sizeof patches, " - patch boundaries (%u patches)", v->num_patches);
    if (il_view_mesh_ready(v)) {              /* the result, or a look at the solve so far */
        snprintf(t, sizeof t,
                 "illum view %s - %s mesh (%d triangles)%s%s - EV %+.1f linear%s%s%s%s",
                 v->o->scene_name, cli_method_name(v->method), (int)(v->mesh_indices / 3),
                 v->mesh_final ? v->mesh_conv : conv, layer, v->exposure,
                 v->wireframe ? " - wireframe" : "", patches, v->normals ? " - normals" : "",
                 v->mesh_final ? "" : " - solving");
    } else if (il_view_mesh_mode(v)) {
        snprintf(t, sizeof t, "illum view %s - %s - solving%s%s", v->o->scene_name,
                 cli_method_name(v->method), conv, failed ? " - FAILED (see terminal)" : "");
    } else {
        snprintf(t, sizeof t,
                 "illum view %s - %s%s - %s%u %s - %.1f s - %.3g Mrays/s - EV %+.1f %s%s",
                 v->o->scene_name, cli_method_name(v->method), conv,
                 v->shown_preview ? "preview " : "", passes,
                 v->method == IL_METHOD_IBL ? "lights" : "spp", secs,
                 secs > 0 ? (double)rays / secs * 1e-6 : 0.0, v->exposure, il_view_op_names[v->op],
                 failed ? " - FAILED (see terminal)" : done ? " - done" : "");
    }
    size_t k = strlen(t);
    if (v->photon_points && (v->method == IL_METHOD_PHOTON || v->method == IL_METHOD_SPPM)) {
        snprintf(t + k, sizeof t - k, " - %d photon points", (int)v->num_points);
        k = strlen(t);
    }
    if (v->spin_fps > 0.0)
        snprintf(t + k, sizeof t - k, " - %.0f fps - moving: %.1f fps, %.1f previews/s", v->fps,
                 v->spin_fps, v->spin_pps);
    else
        snprintf(t + k, sizeof t - k, " - %.0f fps", v->fps);
    glfwSetWindowTitle(v->win, t);
    memcpy(v->title, t, sizeof t);
}

static void on_glfw_error(int code, const char *msg)
{
    cli_error("view: GLFW: %s", msg);
}

int il_viewer_run(const il_viewer_options *o)
{
    viewer v = {.o = o, .method = o->desc.method, .exposure = o->exposure, .op = o->op,
                .mesh_view = true};
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        cli_error("view: cannot open a display (is DISPLAY set? try xvfb-run)");
        return IL_EXIT_RUNTIME;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_FALSE);
    v.win = glfwCreateWindow((int)o->width, (int)o->height, "illum view", NULL, NULL);
    if (!v.win) {
        cli_error("view: cannot create an OpenGL 3.3 core window");
        glfwTerminate();
        return IL_EXIT_RUNTIME;
    }
    glfwMakeContextCurrent(v.win);
    glfwSwapInterval(o->frames ? 0 : 1);
    glfwSetWindowUserPointer(v.win, &v);
    glfwSetKeyCallback(v.win, il_view_on_key);
    glfwSetMouseButtonCallback(v.win, il_view_on_button);
    glfwSetCursorPosCallback(v.win, il_view_on_cursor);
    glfwSetScrollCallback(v.win, il_view_on_scroll);
    if (!il_view_make_image_program(&v) || !il_view_make_mesh_program(&v)) {
        glfwDestroyWindow(v.win);
        glfwTerminate();
        return IL_EXIT_RUNTIME;
    }
    il_view_make_points(&v);

    il_camera_desc start;
    il_scene_get_camera(o->scene, &start);
    v.cam = v.home = il_view_orbit_from(&start);
    v.worker.scene = o->scene;
    v.worker.base = o->desc;
    v.worker.width = o->width;
    v.worker.height = o->height;
    v.worker.cam = il_view_orbit_camera(&v.cam);
    v.worker.method = v.method;
    v.worker.sync_looks = o->frames > 0;
    if (!il_view_worker_start(&v.worker)) {
        cli_error("view: cannot start the render thread");
        glfwDestroyWindow(v.win);
        glfwTerminate();
        return IL_EXIT_RUNTIME;
    }
    /* The start request: the exact start camera (the orbit's round trip
     * through angles could move it by an ulp) at full resolution. */
    il_view_worker_request(&v.worker, &start, v.method, false, il_view_mesh_mode(&v));
    v.baking = il_view_mesh_mode(&v);
    v.bake_method = v.method;

    int rc = IL_EXIT_OK;
    uint32_t frames_after_done = 0;
    const char *keys = o->keys;
    uint32_t passes = 0;
    double secs = 0, last_title = -1, last_frame = glfwGetTime();
    uint64_t rays = 0;
    bool done = false, failed = false, reported = false;
    while (!glfwWindowShouldClose(v.win)) {
        if (o->frames)
            glfwPollEvents();
        else
            glfwWaitEventsTimeout(1.0 / 60.0);
        double now = glfwGetTime();
        il_view_fly(&v, now - last_frame);
        last_frame = now;
        v.fps_frames++;
        if (now - v.fps_start >= 0.5) {
            v.fps = v.fps_frames / (now - v.fps_start);
            v.fps_frames = 0;
            v.fps_start = now;
        }
        if (v.spin_until > 0.0 && now < v.spin_until) {   /* scripted '~' */
            v.cam.yaw = v.spin_yaw0 + (float)(SPIN_RADIANS * (now - v.spin_start) / SPIN_SECONDS);
            il_view_camera_moved(&v);
            v.spin_frames++;
        } else if (v.spin_until > 0.0) {
            v.cam.yaw = v.spin_yaw0 + (float)SPIN_RADIANS;   /* the same end pose on any machine */
            il_view_camera_moved(&v);
            v.spin_fps = v.spin_frames / (now - v.spin_start);
            v.spin_pps = v.spin_previews / (now - v.spin_start);
            v.spin_until = 0.0;
        }
        /* While the camera moves, one preview at a time: the next starts
         * when the last is shown, from the camera as it is then (a newer
         * request would stop each preview before it is drawn). */
        pthread_mutex_lock(&v.worker.mu);
        bool preview_busy = v.previewing && !(v.worker.run_gen == v.worker.gen && v.worker.done);
        pthread_mutex_unlock(&v.worker.mu);
        if (v.moved && !preview_busy) {
            v.moved = false;
            il_view_request(&v, true);
        } else if (!v.moved && v.previewing && now - v.last_move > REST_SECONDS) {
            il_view_request(&v, false);
        }
        il_view_update_layer(&v, now);
        pthread_mutex_lock(&v.worker.mu);
        il_bake_result *baked = v.worker.baked;
        il_method baked_method = v.worker.baked_method;
        bool baked_final = v.worker.baked_final;
        v.worker.baked = NULL;
        if (baked)                    /* a scripted run's worker waits for this */
            pthread_cond_signal(&v.worker.cv);
        if (v.worker.points_fresh) {   /* photon positions: copied under the lock */
            il_view_upload_points(&v, v.worker.points, v.worker.num_points);
            v.worker.points_fresh = false;
        }
        bool fresh = v.worker.fresh;
        uint64_t image_gen = v.worker.image_gen, worker_gen = v.worker.gen;
        if (fresh) {
            il_image_free(&v.shown);
            v.shown = v.worker.image;
            v.worker.image = (il_image){0};
            v.worker.fresh = false;
            v.shown_preview = v.worker.image_preview;
            if (v.shown_preview && v.spin_until > 0.0)
                v.spin_previews++;
            passes = v.worker.passes;
            secs = v.worker.seconds;
            rays = v.worker.rays;
        }
        v.rad_steps = v.worker.rad_steps;
        v.unshot = v.worker.unshot;
        v.radius = v.worker.radius;
        bool current = v.worker.run_gen == v.worker.gen;
        done = current && v.worker.done && !v.worker.fresh;
        failed = current && v.worker.failed;
        if (failed && !reported)
            cli_error("view: %s (method %s)", v.worker.message, cli_method_name(v.method));
        pthread_mutex_unlock(&v.worker.mu);
        reported = failed;
        if (failed)
            v.baking = false;
        bool first_look = false;
        if (baked) {
            v.mesh_final = baked_final;
            if (baked_final)
                v.baking = false;
            else if (il_view_mesh_mode(&v) && baked_method == v.method)
                first_look = ++v.looks == 1;
            int k = 0;
            v.mesh_conv[0] = '\0';
            if (v.unshot >= 0.0)
                k = snprintf(v.mesh_conv, sizeof v.mesh_conv, ", %u steps, unshot %.3g%%",
                             v.rad_steps, 100.0 * v.unshot);
            if (k >= 0 && (size_t)k < sizeof v.mesh_conv)
                snprintf(v.mesh_conv + k, sizeof v.mesh_conv - (size_t)k, ", %u looks", v.looks);
            il_view_upload_mesh(&v, baked, baked_method);
            il_bake_release(baked);
        }
        if (fresh)
            il_view_take_layer(&v, image_gen);
        if (il_view_mesh_mode(&v))
            done = il_view_mesh_ready(&v) && v.mesh_final &&
                   il_view_layer_done(&v, done, worker_gen);
        if (fresh || v.retone) {
            v.retone = false;
            il_view_upload_image(&v);
        }
        if (now - last_title > 0.25 || fresh || baked) {
            update_title(&v, passes, secs, rays, done, failed);
            last_title = now;
        }
        draw(&v);
        if (first_look && o->look_screenshot && !il_view_screenshot(&v, o->look_screenshot))
            rc = IL_EXIT_BAD_INPUT;
        if (o->frames) {
            if (failed) {
                rc = IL_EXIT_RUNTIME;
                break;
            }
            if (v.spin_until > 0.0) {
                /* a scripted '~' orbit is still running */
            } else if (done && !v.previewing && keys && *keys) {
                il_view_scripted_key(&v, *keys++);
                frames_after_done = 0;
            } else if (done && !v.previewing && now - v.last_move > REST_SECONDS &&
                       ++frames_after_done >= o->frames) {
                if (o->screenshot && !il_view_screenshot(&v, o->screenshot))
                    rc = IL_EXIT_BAD_INPUT;
                update_title(&v, passes, secs, rays, done, failed);
                printf("%s\n", v.title);
                glfwSwapBuffers(v.win);
                break;
            }
        }
        glfwSwapBuffers(v.win);
    }
    il_view_worker_stop(&v.worker);
    il_image_free(&v.shown);
    glDeleteTextures(1, &v.tex);
    glDeleteProgram(v.prog);
    glDeleteVertexArrays(1, &v.vao);
    glDeleteProgram(v.mesh_prog);
    glDeleteVertexArrays(1, &v.mesh_vao);
    glDeleteBuffers(1, &v.mesh_vbo);
    glDeleteBuffers(1, &v.mesh_ibo);
    glDeleteVertexArrays(1, &v.normal_vao);
    il_view_free_points(&v);
    il_view_free_mesh(&v);
    glDeleteBuffers(1, &v.normal_vbo);
    glfwDestroyWindow(v.win);
    glfwTerminate();
    return rc;
}
