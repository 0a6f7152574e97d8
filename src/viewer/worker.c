/* The viewer's render thread: il_render with a progress callback; every
 * callback's film is complete (il_render_progress), so each is resolved and
 * handed to the window, and a newer request stops the render after its
 * current pass. */
#include "viewer/worker.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static bool stale(il_view_worker *w)
{
    return w->quit || w->gen != w->run_gen;
}

/* Resolves the film and publishes it; false when a newer request came. */
static bool publish(il_view_worker *w, const il_film *film, uint32_t passes, double seconds,
                    uint64_t rays, bool preview)
{
    il_image img = {0};
    il_error err = {0};
    if (il_film_resolve(film, &img, &err) != IL_OK)
        return false;
    pthread_mutex_lock(&w->mu);
    bool ok = !stale(w);
    if (ok) {
        il_image_free(&w->image);
        w->image = img;
        img = (il_image){0};
        w->fresh = true;
        w->image_preview = preview;
        w->image_gen = w->run_gen;
        w->passes = passes;
        w->seconds = seconds;
        w->rays = rays;
    }
    pthread_mutex_unlock(&w->mu);
    il_image_free(&img);
    return ok;
}

typedef struct pass_ctx {
    il_view_worker *w;
    bool preview;
} pass_ctx;

static bool on_progress(const il_render_progress *p, void *user)
{
    pass_ctx *c = user;
    pthread_mutex_lock(&c->w->mu);
    if (!stale(c->w))
        c->w->radius = p->radius;
    pthread_mutex_unlock(&c->w->mu);
    return publish(c->w, p->film, p->passes_done, p->seconds, p->rays, c->preview);
}

/* Photon mapping and SPPM: the traced photons' positions for the window's
 * photon points, every k-th so that at most IL_VIEW_MAX_POINTS are kept;
 * the caustic map's (which 1) join the global map's (which 0). */
static void on_photons(const float *xyz, size_t count, int which, void *user)
{
    il_view_worker *w = user;
    size_t step = count / IL_VIEW_MAX_POINTS + 1, n = (count + step - 1) / step;
    pthread_mutex_lock(&w->mu);
    size_t keep = which == 1 ? w->num_points : 0;
    float *p = stale(w) ? NULL : realloc(w->points, (keep + n) * 3 * sizeof *p + 1);
    if (p) {
        for (size_t i = 0; i < n; i++)
            memcpy(p + 3 * (keep + i), xyz + 3 * i * step, 3 * sizeof *p);
        w->points = p;
        w->num_points = keep + n;
        w->points_fresh = true;
    }
    pthread_mutex_unlock(&w->mu);
}

/* Stops a radiosity solve once a newer request (or quit) came. */
static bool on_step(const il_radiosity_progress *p, void *user)
{
    il_view_worker *w = user;
    pthread_mutex_lock(&w->mu);
    bool go = !stale(w);
    if (go) {
        w->rad_steps = p->step;
        w->unshot = p->unshot_fraction;
    }
    pthread_mutex_unlock(&w->mu);
    return go;
}

/* hr's solve and photon mapping's set-up stop likewise (closing the window
 * during an hr refinement of minutes waited for its end before). */
static bool still_wanted(il_view_worker *w)
{
    pthread_mutex_lock(&w->mu);
    bool go = !stale(w);
    pthread_mutex_unlock(&w->mu);
    return go;
}

static bool on_hr_step(const il_hr_progress *p, void *user)
{
    (void)p;
    return still_wanted(user);
}

static bool on_photon_step(const il_photon_progress *p, void *user)
{
    (void)p;
    return still_wanted(user);
}

static bool on_linespace_step(const il_linespace_progress *p, void *user)
{
    (void)p;
    return still_wanted(user);
}

/* Points the render's method options `field` at `copy`: the caller's
 * options (or the defaults) with on_step set to fn, called with the worker. */
#define WATCH_STEPS(d, field, copy, fn, w)                                                      \
    do {                                                                                        \
        if ((d).field)                                                                          \
            (copy) = *(d).field;                                                                \
        (copy).on_step = (fn);                                                                  \
        (copy).on_step_user = (w);                                                              \
        (d).field = &(copy);                                                                    \
    } while (0)

static double now_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* A deep copy that il_bake_release frees (the looks live only during the
 * callback); NULL without memory. */
static il_bake_result *copy_bake(const il_bake_result *b)
{
    il_bake_result *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    c->meshes = calloc(b->num_meshes ? b->num_meshes : 1u, sizeof *c->meshes);
    if (!c->meshes) {
        free(c);
        return NULL;
    }
    c->num_meshes = b->num_meshes;
    bool ok = true;
    for (uint32_t m = 0; m < b->num_meshes; m++) {
        const il_bake_mesh *s = &b->meshes[m];
        il_bake_mesh *d = &c->meshes[m];
        *d = *s;
        size_t nv = (size_t)s->num_vertices * 3 * sizeof(float);
        size_t ni = (size_t)s->num_triangles * 3 * sizeof(uint32_t);
        size_t np = (size_t)s->num_triangles * sizeof(uint32_t);
        d->positions = malloc(nv + 1);
        d->normals = malloc(nv + 1);
        d->radiance = malloc(nv + 1);
        d->indices = malloc(ni + 1);
        d->patches = malloc(np + 1);
        if (!d->positions || !d->normals || !d->radiance || !d->indices || !d->patches) {
            ok = false;
            continue;
        }
        memcpy(d->positions, s->positions, nv);
        memcpy(d->normals, s->normals, nv);
        memcpy(d->radiance, s->radiance, nv);
        memcpy(d->indices, s->indices, ni);
        memcpy(d->patches, s->patches, np);
    }
    if (!ok) {
        il_bake_release(c);
        return NULL;
    }
    return c;
}

/* Sets a bake for the window unless a newer request came; takes b. */
static bool publish_bake(il_view_worker *w, il_bake_result *b, il_method method, bool final)
{
    pthread_mutex_lock(&w->mu);
    bool ok = !stale(w);
    if (ok) {
        il_bake_release(w->baked);
        w->baked = b;
        w->baked_method = method;
        w->baked_final = final;
        b = NULL;
    }
    pthread_mutex_unlock(&w->mu);
    il_bake_release(b);
    return ok;
}

typedef struct look_ctx {
    il_view_worker *w;
    il_method method;
} look_ctx;

/* il_bake_progressive's look after a solver step: at most 20 a second are
 * copied for the window (it draws the latest); scripted runs (sync_looks)
 * hand over every look and wait until the window took it, so that the
 * window draws each. */
static bool on_look(const il_bake_result *cur, void *user)
{
    look_ctx *c = user;
    il_view_worker *w = c->w;
    double t = now_seconds();
    pthread_mutex_lock(&w->mu);
    bool go = !stale(w), due = w->sync_looks || t - w->last_look >= 0.05;
    pthread_mutex_unlock(&w->mu);
    if (!go || !due)
        return go;
    il_bake_result *copy = copy_bake(cur);
    if (!copy)
        return true;
    w->last_look = t;
    if (!publish_bake(w, copy, c->method, false))
        return false;
    if (!w->sync_looks)
        return true;
    pthread_mutex_lock(&w->mu);
    while (w->baked && !stale(w))     /* the window signals cv when it takes it */
        pthread_cond_wait(&w->cv, &w->mu);
    go = !stale(w);
    pthread_mutex_unlock(&w->mu);
    return go;
}

/* The per-vertex solution of radiosity or hr (il_bake_progressive), for the
 * window's Gouraud-shaded mesh: a look after solver steps, then the result. */
static il_status bake(il_view_worker *w, il_method method, il_error *err)
{
    il_render_desc d = w->base;
    d.method = method;
    il_radiosity_desc rd = {0};
    il_hr_desc hd = {0};
    WATCH_STEPS(d, radiosity, rd, on_step, w);
    WATCH_STEPS(d, hr, hd, on_hr_step, w);
    il_bake_result *res = NULL;
    look_ctx look = {w, method};
    w->last_look = now_seconds();     /* the first look 0.05 s into the solve */
    il_status st = il_bake_progressive(w->scene, &d, on_look, &look, &res, err);
    if (st != IL_OK)
        return st;
    publish_bake(w, res, method, true);
    return IL_OK;
}

static void *worker_main(void *arg)
{
    il_view_worker *w = arg;
    il_film *film = NULL;
    for (;;) {
        pthread_mutex_lock(&w->mu);
        while (!w->quit && w->gen == w->run_gen)
            pthread_cond_wait(&w->cv, &w->mu);
        if (w->quit) {
            pthread_mutex_unlock(&w->mu);
            break;
        }
        w->run_gen = w->gen;
        il_camera_desc cam = w->cam;
        bool preview = w->preview;
        bool want_bake = w->bake;
        il_method method = w->method;
        w->done = w->failed = false;
        w->unshot = -1.0;
        w->radius = 0.0;
        pthread_mutex_unlock(&w->mu);

        il_error err = {0};
        if (want_bake) {
            il_status bst = bake(w, method, &err);
            pthread_mutex_lock(&w->mu);
            if (w->run_gen == w->gen) {
                w->done = true;
                w->failed = bst != IL_OK;
                if (bst != IL_OK)
                    snprintf(w->message, sizeof w->message, "%s", err.message);
            }
            pthread_mutex_unlock(&w->mu);
            continue;
        }
        il_status st = il_scene_set_camera(w->scene, &cam, &err);
        /* Preview: a quarter of the pixels' side, one path per pixel. */
        uint32_t fw = preview ? (w->width + 3) / 4 : w->width;
        uint32_t fh = preview ? (w->height + 3) / 4 : w->height;
        if (st == IL_OK && (!film || il_film_width(film) != fw || il_film_height(film) != fh)) {
            il_film_release(film);
            film = NULL;
            st = il_film_create(fw, fh, &film, &err);
        }
        il_render_stats rs = {0};
        pass_ctx ctx = {w, preview};
        if (st == IL_OK) {
            il_render_desc d = w->base;
            d.method = preview ? IL_METHOD_PT : method;
            if (preview) {
                d.spp = 1;
                d.time_limit = 0;
            } else if (d.spp == 0) {
                d.time_limit = 3e7; /* no sample count: refine until the next request
                                       (il_render allows at most a year) */
            }
            d.progress = on_progress;
            d.progress_user = &ctx;
            /* A newer request ends a solve or a set-up early. */
            il_radiosity_desc rd = {0};
            il_photon_desc pd = {0};
            il_linespace_desc ld = {0};
            WATCH_STEPS(d, radiosity, rd, on_step, w);
            WATCH_STEPS(d, photon, pd, on_photon_step, w);
            WATCH_STEPS(d, linespace, ld, on_linespace_step, w);
            if (!preview) {
                pd.on_photons = on_photons;
                pd.on_photons_user = w;
            }
            st = il_render(w->scene, film, &d, &rs, &err);
        }
        /* Publish the final film too: not every method calls back after its last pass. */
        if (st == IL_OK)
            publish(w, film, rs.spp, rs.seconds, rs.rays, preview);
        pthread_mutex_lock(&w->mu);
        if (w->run_gen == w->gen) {
            w->done = true;
            if (st != IL_OK) {
                w->failed = true;
                snprintf(w->message, sizeof w->message, "%s", err.message);
            }
        }
        pthread_mutex_unlock(&w->mu);
    }
    il_film_release(film);
    return NULL;
}

bool il_view_worker_start(il_view_worker *w)
{
    pthread_mutex_init(&w->mu, NULL);
    pthread_cond_init(&w->cv, NULL);
    w->gen = 1;
    w->run_gen = 0;
    return pthread_create(&w->thread, NULL, worker_main, w) == 0;
}

void il_view_worker_request(il_view_worker *w, const il_camera_desc *cam, il_method method,
                            bool preview, bool bake)
{
    pthread_mutex_lock(&w->mu);
    w->gen++;
    w->cam = *cam;
    w->method = method;
    w->preview = preview;
    w->bake = bake;
    w->done = w->failed = false;
    pthread_cond_signal(&w->cv);
    pthread_mutex_unlock(&w->mu);
}

void il_view_worker_stop(il_view_worker *w)
{
    pthread_mutex_lock(&w->mu);
    w->quit = true;
    pthread_cond_signal(&w->cv);
    pthread_mutex_unlock(&w->mu);
    pthread_join(w->thread, NULL);
    il_image_free(&w->image);
    il_bake_release(w->baked);
    free(w->points);
    pthread_mutex_destroy(&w->mu);
    pthread_cond_destroy(&w->cv);
}
