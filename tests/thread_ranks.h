/* Processes of a split render (il_distrib, illum.h) simulated in one test
 * program, without MPI: each rank is a thread, the exchange a shared buffer
 * between two barriers, the tile counter an atomic. */
#ifndef IL_TESTS_THREAD_RANKS_H
#define IL_TESTS_THREAD_RANKS_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "illum/illum.h"

#define THREAD_RANKS_MAX 3

typedef struct thread_exchange {
    pthread_barrier_t barrier;
    int size;
    bool drop_last;                /* lose the last rank's bytes (a broken exchange) */
    const void *data[THREAD_RANKS_MAX];
    size_t bytes[THREAD_RANKS_MAX];
    _Atomic uint64_t tiles;        /* il_distrib.claim's counter */
} thread_exchange;

/* One rank: what il_distrib.user points at. */
typedef struct thread_rank {
    thread_exchange *x;
    int rank;
} thread_rank;

static inline void thread_exchange_init(thread_exchange *x, int size, bool drop_last)
{
    memset(x, 0, sizeof *x);
    x->size = size;
    x->drop_last = drop_last;
    pthread_barrier_init(&x->barrier, NULL, (unsigned)size);
}

static inline void thread_exchange_destroy(thread_exchange *x) { pthread_barrier_destroy(&x->barrier); }

/* il_distrib.allgather: every rank's bytes in rank order. */
static inline int thread_allgather(void *user, const void *data, size_t bytes, void **out, size_t *counts)
{
    thread_rank *me = user;
    thread_exchange *x = me->x;
    x->data[me->rank] = data;
    x->bytes[me->rank] = bytes;
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

/* il_distrib.claim: tiles on demand from the shared counter. */
static inline uint64_t thread_claim(void *user, uint64_t count)
{
    thread_rank *me = user;
    return atomic_fetch_add(&me->x->tiles, count);
}

static inline int thread_failing_allgather(void *user, const void *data, size_t bytes, void **out,
                                           size_t *counts)
{
    (void)user, (void)data, (void)bytes, (void)counts;
    *out = NULL;
    return 1;
}

/* Rank r's distrib over x (dynamic: with tiles on demand). */
static inline il_distrib thread_distrib(thread_rank *me, thread_exchange *x, int r, bool dynamic)
{
    *me = (thread_rank){x, r};
    return (il_distrib){.rank = r, .size = x->size, .allgather = thread_allgather, .user = me,
                        .claim = dynamic ? thread_claim : NULL};
}

#endif
