/* One render split across processes through the library's il_distrib hook
 * (illum.h, docs/distributed.md), without MPI: each "process" is a thread
 * with its own film, the exchange a shared buffer between two barriers.
 * The films of all ranks summed must be the single-process film bit for
 * bit, for every method: the path tracer, photon mapping (with and without
 * final gather), SPPM, progressive radiosity (shooting and gathering),
 * hierarchical radiosity, IBL, Linespace and reflective shadow maps; a
 * malformed distrib and a failing exchange are errors, not crashes. */
#include <string.h>

#include "scene_build.h"
#include "illum/illum.h"
#include "thread_ranks.h"

#define W 48
#define H 48
typedef struct rank_job {
    thread_rank me;
    il_distrib distrib;
    const il_scene *scene;
    il_render_desc desc;
    il_film *film;
    il_status status;
    il_error err;
} rank_job;

static void *run_rank(void *arg)
{
    rank_job *job = arg;
    job->desc.distrib = &job->distrib;
    job->status = il_render(job->scene, job->film, &job->desc, NULL, &job->err);
    return NULL;
}

/* The render of desc as `size` ranks against one process; dynamic: tiles
 * claimed on demand (il_distrib.claim) rather than dealt. */
static uint64_t check_split_as(const il_scene *scene, il_render_desc desc, int size, bool dynamic,
                               const char *what)
{
    il_error err = {0};
    il_film *whole = NULL;
    CHECK_OK(il_film_create(W, H, &whole, &err), &err);
    CHECK_OK(il_render(scene, whole, &desc, NULL, &err), &err);

    thread_exchange x;
    thread_exchange_init(&x, size, false);
    rank_job jobs[THREAD_RANKS_MAX];
    pthread_t threads[THREAD_RANKS_MAX];
    for (int r = 0; r < size; r++) {
        jobs[r] = (rank_job){.scene = scene, .desc = desc};
        jobs[r].distrib = thread_distrib(&jobs[r].me, &x, r, dynamic);
        CHECK_OK(il_film_create(W, H, &jobs[r].film, &err), &err);
        pthread_create(&threads[r], NULL, run_rank, &jobs[r]);
    }
    for (int r = 0; r < size; r++)
        pthread_join(threads[r], NULL);
    thread_exchange_destroy(&x);

    size_t n = 4 * (size_t)W * H, differ = 0;
    const double *a = il_film_data(whole);
    double total = 0.0;
    for (size_t i = 0; i < n; i++) {
        double sum = 0.0;
        for (int r = 0; r < size; r++)
            sum += il_film_data(jobs[r].film)[i];
        differ += sum != a[i];
        total += a[i];
    }
    for (int r = 0; r < size; r++) {
        CHECK_OK(jobs[r].status, &jobs[r].err);
        il_film_release(jobs[r].film);
    }
    printf("%-28s %d ranks%s: %zu of %zu film values differ from one process (film sum %.6g)\n", what,
           size, dynamic ? ", tiles on demand" : "", differ, n, total);
    CHECK(differ == 0);
    CHECK(total > 0.0);
    il_film_release(whole);
    /* Claimed tiles: none (a method without the camera pass) or all 9. */
    uint64_t claimed = atomic_load(&x.tiles);
    CHECK(claimed == 0 || claimed >= 9);
    return claimed;
}

static void check_split(const il_scene *scene, il_render_desc desc, int size, const char *what)
{
    check_split_as(scene, desc, size, false, what);
    check_split_as(scene, desc, size, true, what);
}

int main(void)
{
    il_error err = {0};
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();
    il_render_desc base = {.spp = 2, .max_depth = 4, .seed = 7, .threads = 1};

    il_photon_desc pd = {.photons = 20000};
    il_render_desc photon = base;
    photon.method = IL_METHOD_PHOTON;
    photon.photon = &pd;
    check_split(s, photon, 2, "photon");
    check_split(s, photon, 3, "photon");
    il_photon_desc fg = {.photons = 20000, .final_gather = 4};
    photon.photon = &fg;
    check_split(s, photon, 2, "photon, final gather");

    il_photon_desc sd = {.photons = 5000};
    il_render_desc sppm = base;
    sppm.method = IL_METHOD_SPPM;
    sppm.spp = 3;
    sppm.photon = &sd;
    check_split(s, sppm, 2, "sppm");
    check_split(s, sppm, 3, "sppm");

    il_render_desc rad = base;
    rad.method = IL_METHOD_RADIOSITY;
    il_radiosity_desc shoot = {.subdivisions = 2, .form_factors = IL_FF_RAYCAST, .ray_samples = 256, .max_steps = 60};
    rad.radiosity = &shoot;
    check_split(s, rad, 2, "radiosity, shooting");
    check_split(s, rad, 3, "radiosity, shooting");
    il_radiosity_desc gather = shoot;
    gather.solver = IL_SOLVER_JACOBI;
    gather.max_steps = 8;
    rad.radiosity = &gather;
    check_split(s, rad, 2, "radiosity, gathering");

    il_render_desc hr = base;
    hr.method = IL_METHOD_HR;
    check_split(s, hr, 2, "hierarchical radiosity");

    il_render_desc pt = base;
    pt.method = IL_METHOD_PT;
    check_split_as(s, pt, 3, false, "path tracing");
    CHECK(check_split_as(s, pt, 3, true, "path tracing") >= 9);

    il_linespace_desc lsd = {.n = 2, .inject_rays = 20000};
    il_render_desc ls = base;
    ls.method = IL_METHOD_LINESPACE;
    ls.linespace = &lsd;
    check_split(s, ls, 2, "linespace");

    /* The box lit by a spot and a sky through its open front as well. */
    il_scene *lit = NULL;
    CHECK_OK(il_scene_load("cornell", NULL, &lit, &err), &err);
    if (lit) {
        il_light_desc spot = {.type = IL_LIGHT_SPOT, .position = {0.0f, 0.5f, 0.2f},
                              .direction = {0.0f, -1.0f, -0.3f}, .intensity = {2.0f, 2.0f, 2.0f},
                              .spot_angle = 40.0f};
        CHECK_OK(il_scene_add_light(lit, &spot, &err), &err);
        il_environment_desc sky = {.radiance = {0.2f, 0.3f, 0.5f}};
        CHECK_OK(il_scene_set_environment(lit, &sky, &err), &err);
        CHECK_OK(il_scene_commit(lit, &err), &err);
        il_rsm_desc rsmd = {.resolution = 64, .samples = 32};
        il_render_desc rsm = base;
        rsm.method = IL_METHOD_RSM;
        rsm.rsm = &rsmd;
        check_split(lit, rsm, 2, "rsm");
        il_ibl_desc ibd = {.lights = 32, .batch = 8};
        il_render_desc ibl = base;
        ibl.method = IL_METHOD_IBL;
        ibl.ibl = &ibd;
        check_split(lit, ibl, 2, "ibl");
        check_split(lit, ibl, 3, "ibl");
        il_scene_release(lit);
    }

    /* Malformed or failing: errors. */
    il_film *film = NULL;
    CHECK_OK(il_film_create(W, H, &film, &err), &err);
    il_distrib bad = {.rank = 2, .size = 2, .allgather = thread_allgather};
    photon.photon = &pd;
    photon.distrib = &bad;
    CHECK(il_render(s, film, &photon, NULL, &err) == IL_ERR_INVALID);
    printf("rank out of range: %s\n", err.message);
    il_distrib none = {.rank = 0, .size = 2};
    photon.distrib = &none;
    CHECK(il_render(s, film, &photon, NULL, &err) == IL_ERR_INVALID);
    il_distrib timed = {.rank = 0, .size = 2, .allgather = thread_allgather};
    photon.distrib = &timed;
    photon.time_limit = 1.0;
    CHECK(il_render(s, film, &photon, NULL, &err) == IL_ERR_INVALID);
    photon.time_limit = 0.0;
    il_distrib broken = {.rank = 0, .size = 2, .allgather = thread_failing_allgather};
    photon.distrib = &broken;
    CHECK(il_render(s, film, &photon, NULL, &err) == IL_ERR_RUNTIME);
    printf("failing exchange: %s\n", err.message);
    il_film_release(film);
    il_scene_release(s);
    return check_report();
}
