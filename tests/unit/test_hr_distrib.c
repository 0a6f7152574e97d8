/* Hierarchical radiosity split across processes through the il_distrib
 * hook (src/methods/hr/hr_distrib.c), without MPI: each "process" is a
 * thread, the exchange a shared buffer between two barriers.  Every rank
 * must end with the single-process hierarchy and solution: the same
 * per-vertex radiance bit for bit, the same element, link and visibility-ray
 * counts, also when the ranks run different thread counts; an exchange that
 * fails or loses a rank's links is an error on every rank, not a crash. */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "illum/illum.h"
#include "methods/hr/hr.h"

#define MAX_RANKS 3

typedef struct exchange {
    pthread_barrier_t barrier;
    int size;
    bool drop_last;  /* lose the last rank's bytes (a broken exchange) */
    const void *data[MAX_RANKS];
    size_t bytes[MAX_RANKS];
} exchange;

typedef struct rank_job {
    exchange *x;
    il_distrib distrib;
    const il_scene *scene;
    il_render_desc desc;
    il_patch_mesh *mesh;
    il_vec3 *radiance;
    il_render_stats stats;
    il_status status;
    il_error err;
} rank_job;

/* il_distrib.allgather: every rank's bytes in rank order. */
static int allgather(void *user, const void *data, size_t bytes, void **out, size_t *counts)
{
    rank_job *job = user;
    exchange *x = job->x;
    x->data[job->distrib.rank] = data;
    x->bytes[job->distrib.rank] = bytes;
    pthread_barrier_wait(&x->barrier);
    int n = x->drop_last ? x->size - 1 : x->size;
    size_t total = 0;
    for (int r = 0; r < n; r++)
        total += x->bytes[r];
    int rc = 0;
    *out = total ? malloc(total) : NULL;
    if (total && !*out)
        rc = 1;
    size_t at = 0;
    for (int r = 0; r < x->size; r++) {
        counts[r] = r < n ? x->bytes[r] : 0;
        if (*out && r < n && x->bytes[r])
            memcpy((char *)*out + at, x->data[r], x->bytes[r]);
        at += counts[r];
    }
    /* Nobody may change its data before everyone has copied it. */
    pthread_barrier_wait(&x->barrier);
    return rc;
}

static int failing_allgather(void *user, const void *data, size_t bytes, void **out, size_t *counts)
{
    (void)user, (void)data, (void)bytes, (void)counts;
    *out = NULL;
    return 1;
}

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
    exchange x = {.size = size, .drop_last = drop_last};
    pthread_barrier_init(&x.barrier, NULL, (unsigned)size);
    pthread_t tid[MAX_RANKS];
    for (int r = 0; r < size; r++) {
        jobs[r] = (rank_job){.x = &x, .scene = scene, .desc = desc};
        jobs[r].desc.threads = threads[r];
        jobs[r].distrib =
            (il_distrib){.rank = r, .size = size, .allgather = allgather, .user = &jobs[r]};
        pthread_create(&tid[r], NULL, run_rank, &jobs[r]);
    }
    for (int r = 0; r < size; r++)
        pthread_join(tid[r], NULL);
    pthread_barrier_destroy(&x.barrier);
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
    rank_job jobs[MAX_RANKS];
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
    il_scene *s = NULL;
    CHECK_OK(il_scene_load("cornell", NULL, &s, &err), &err);
    if (!s)
        return check_report();
    CHECK_OK(il_scene_commit(s, &err), &err);
    il_hr_desc hd = {.bf_eps = 0.03f};
    il_render_desc desc = {.method = IL_METHOD_HR, .seed = 7, .threads = 1, .hr = &hd};

    const int one[MAX_RANKS] = {1, 1, 1}, mixed[MAX_RANKS] = {2, 1, 3};
    check_split(s, desc, 2, one, "cornell");
    check_split(s, desc, 3, one, "cornell");
    check_split(s, desc, 3, mixed, "cornell, mixed threads");
    il_hr_desc odd = {.bf_eps = 0.03f, .vis_rays = 9};
    desc.hr = &odd;
    check_split(s, desc, 2, one, "cornell, 9 rays");
    desc.hr = &hd;

    /* A broken exchange: the last rank's links lost, on every rank. */
    rank_job jobs[MAX_RANKS];
    run_split(s, desc, 2, one, true, jobs);
    for (int r = 0; r < 2; r++) {
        CHECK(jobs[r].status == IL_ERR_RUNTIME);
        CHECK(strstr(jobs[r].err.message, "bytes of links") != NULL);
    }
    printf("lost links: %s\n", jobs[0].err.message);
    free_jobs(jobs, 2);
    /* A failing exchange and a rank out of range. */
    il_distrib broken = {.rank = 0, .size = 2, .allgather = failing_allgather};
    desc.distrib = &broken;
    CHECK(il_hr_run(s, &desc, NULL, NULL, NULL, &err) == IL_ERR_RUNTIME);
    printf("failing exchange: %s\n", err.message);
    il_distrib bad = {.rank = 2, .size = 2, .allgather = allgather};
    desc.distrib = &bad;
    CHECK(il_hr_run(s, &desc, NULL, NULL, NULL, &err) == IL_ERR_INVALID);
    printf("rank out of range: %s\n", err.message);
    il_scene_release(s);
    return check_report();
}
