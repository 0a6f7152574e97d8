/* Per-thread chunked arenas for elements and links (hr.h).  A thread takes
 * from its own pool only, so there is no lock; a chunk is malloc'ed when
 * the newest one is full (rare: chunks hold thousands of items), never per
 * item.  Everything is freed at once at the end. */
#include <stdalign.h>
#include <stdlib.h>
#include <string.h>

#include "methods/hr/hr.h"

#define ELEMS_PER_CHUNK 2048u  /* a multiple of 4 */
#define LINKS_PER_CHUNK 16384u

struct il_hr_chunk {
    il_hr_chunk *next;
    alignas(64) unsigned char data[];
};

void il_hr_pool_init(il_hr_pool *pool) { memset(pool, 0, sizeof *pool); }

static void free_chain(il_hr_chunk *c)
{
    while (c) {
        il_hr_chunk *n = c->next;
        free(c);
        c = n;
    }
}

void il_hr_pool_free(il_hr_pool *pool)
{
    free_chain(pool->elem_chunks);
    free_chain(pool->link_chunks);
    memset(pool, 0, sizeof *pool);
}

static il_hr_chunk *new_chunk(il_hr_pool *pool, il_hr_chunk **head, size_t bytes)
{
    il_hr_chunk *c = malloc(sizeof *c + bytes);
    if (!c) {
        pool->failed = true;
        return NULL;
    }
    c->next = *head;
    *head = c;
    pool->bytes += sizeof *c + bytes;
    return c;
}

il_hr_elem *il_hr_pool_elems4(il_hr_pool *pool)
{
    if (pool->elem_used + 4 > pool->elem_cap) {
        if (!new_chunk(pool, &pool->elem_chunks, ELEMS_PER_CHUNK * sizeof(il_hr_elem)))
            return NULL;
        pool->elem_used = 0;
        pool->elem_cap = ELEMS_PER_CHUNK;
    }
    il_hr_elem *e = (il_hr_elem *)pool->elem_chunks->data + pool->elem_used;
    pool->elem_used += 4;
    return e;
}

void il_hr_pool_unget4(il_hr_pool *pool) { pool->elem_used -= 4; }

il_hr_link *il_hr_pool_link(il_hr_pool *pool)
{
    if (pool->free_links) {
        il_hr_link *l = pool->free_links;
        pool->free_links = l->next;
        return l;
    }
    if (pool->link_used >= pool->link_cap) {
        if (!new_chunk(pool, &pool->link_chunks, LINKS_PER_CHUNK * sizeof(il_hr_link)))
            return NULL;
        pool->link_used = 0;
        pool->link_cap = LINKS_PER_CHUNK;
    }
    return (il_hr_link *)pool->link_chunks->data + pool->link_used++;
}

void il_hr_pool_put_link(il_hr_pool *pool, il_hr_link *link)
{
    link->next = pool->free_links;
    pool->free_links = link;
}
