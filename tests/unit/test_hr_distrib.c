/* Hierarchical radiosity split across processes through the il_distrib
 * hook (src/methods/hr/hr_distrib.c), without MPI: each "process" is a
 * thread, the exchange a shared buffer between two barriers.  Every rank
 * must end with the single-process hierarchy and solution: the same
 * per-vertex radiance bit for bit, the same element, link and visibility-ray
 * counts, also when the ranks run different thread counts; an exchange that
 * fails or loses a rank's links is an error on every rank, not a crash. */
#include <stdlib.h>
#include <string.h>

#include "scene_build.h"
#include "illum/illum.h"
#include "methods/hr/hr.h"
#include "thread_ranks.h"

typedef struct rank_job {
    thread_rank me;
    il_distrib distrib;
    const il_scene *scene;
    il_render_desc desc;
    il_patch_mesh *mesh;
    il_vec3 *radiance;
    il_render_stats stats;
    il_status status;
    il_error err;
} rank_job;

static void *run_rank(void *arg)
{
    rank_job *job = arg;
    job->desc.distrib = &job->distrib;
    job->status = il_hr_run(job->scene, &job->desc, &job->mesh, &job->radiance, &job->stats,
                            &job->err);
    return NULL;
}

/* Runs desc as `size` ranks (rank r with threads[r] threads); returns the
 * statuses in jobs. */
static void run_split(const il_scene *scene, il_render_desc desc, int size, const int *threads,
                      bool drop_last, rank_job *jobs)
{
    thread_exchange x;
    thread_exchange_init(&x, size, drop_last);
    pthread_t tid[THREAD_RANKS_MAX];
    for (int r = 0; r < size; r++) {
        jobs[r] = (rank_job){.scene = scene, .desc = desc};
        jobs[r].desc.threads = threads[r];
        jobs[r].distrib = thread_distrib(&jobs[r].me, &x, r, false);
        pthread_create(&tid[r], NULL, run_rank, &jobs[r]);
    }
    for (int r = 0; r < size; r++)
        pthread_join(tid[r], NULL);
    thread_exchange_destroy(&x);
}

static void free_jobs(rank_job *jobs, int size)
{
    for (int r = 0; r < size; r++) {
        il_patch_mesh_release(jobs[r].mesh);
        free(jobs[r].radiance);
    }
}

static void check_split(const il_scene *scene, il_render_desc desc, int size, const int *threads,
                        const char *what)
{
    il_error err = {0};
    il_patch_mesh *mesh = NULL;
    il_vec3 *rad = NULL;
    il_render_stats one;
    CHECK_OK(il_hr_run(scene, &desc, &mesh, &rad, &one, &err), &err);
    if (!mesh)
        return;
    rank_job jobs[THREAD_RANKS_MAX];
    run_split(scene, desc, size, threads, false, jobs);
    for (int r = 0; r < size; r++) {
        CHECK_OK(jobs[r].status, &jobs[r].err);
        if (jobs[r].status != IL_OK)
            continue;
        const il_hr_stats *a = &one.hr, *b = &jobs[r].stats.hr;
        CHECK(jobs[r].mesh->num_vertices == mesh->num_vertices);
        CHECK(jobs[r].mesh->num_patches == mesh->num_patches);
        CHECK(a->elements == b->elements && a->links == b->links &&
              a->iterations == b->iterations && a->visibility_rays == b->visibility_rays);
        bool same = jobs[r].mesh->num_vertices == mesh->num_vertices &&
                    memcmp(jobs[r].radiance, rad, mesh->num_vertices * sizeof *rad) == 0;
        CHECK(same);
        printf("%-26s rank %d of %d (%d threads): %s; %llu elements, %llu links, %llu rays\n",
               what, r, size, threads[r], same ? "the single-process radiance" : "DIFFERS",
               (unsigned long long)b->elements, (unsigned long long)b->links,
               (unsigned long long)b->visibility_rays);
    }
    free_jobs(jobs, size);
    il_patch_mesh_release(mesh);
    free(rad);
}

int main(void)
{
    il_error err = {0};
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();
    il_hr_desc hd = {.bf_eps = 0.03f};
    il_render_desc desc = {.method = IL_METHOD_HR, .seed = 7, .threads = 1, .hr = &hd};

    const int one[THREAD_RANKS_MAX] = {1, 1, 1}, mixed[THREAD_RANKS_MAX] = {2, 1, 3};
    check_split(s, desc, 2, one, "cornell");
    check_split(s, desc, 3, one, "cornell");
    check_split(s, desc, 3, mixed, "cornell, mixed threads");
    il_hr_desc odd = {.bf_eps = 0.03f, .vis_rays = 9};
    desc.hr = &odd;
    check_split(s, desc, 2, one, "cornell, 9 rays");
    desc.hr = &hd;

    /* A broken exchange: the last rank's links lost, on every rank. */
    rank_job jobs[THREAD_RANKS_MAX];
    run_split(s, desc, 2, one, true, jobs);
    for (int r = 0; r < 2; r++) {
        CHECK(jobs[r].status == IL_ERR_RUNTIME);
        CHECK(strstr(jobs[r].err.message, "bytes of links") != NULL);
    }
    printf("lost links: %s\n", jobs[0].err.message);
    free_jobs(jobs, 2);
    /* A failing exchange and a rank out of range. */
    il_distrib broken = {.rank = 0, .size = 2, .allgather = thread_failing_allgather};
    desc.distrib = &broken;
    CHECK(il_hr_run(s, &desc, NULL, NULL, NULL, &err) == IL_ERR_RUNTIME);
    printf("failing exchange: %s\n", err.message);
    il_distrib bad = {.rank = 2, .size = 2, .allgather = thread_allgather};
    desc.distrib = &bad;
    CHECK(il_hr_run(s, &desc, NULL, NULL, NULL, &err) == IL_ERR_INVALID);
    printf("rank out of range: %s\n", err.message);
    il_scene_release(s);
    return check_report();
}
