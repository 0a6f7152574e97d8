/* The photon map of the shared kernels on the CPU; see kernel_photon_map.h. */
#include "kernel/kernel_photon_map.h"

#include <stdlib.h>
#include <string.h>
#include "core/error.h"
#include "kernel/kernel_photon_gather.h"

uint32_t il_kgrid_hash_mask(uint64_t num_slots)
{
    uint64_t size = 1024;
    while (size < num_slots / 2 && size < (1u << 26))
        size <<= 1;
    return (uint32_t)(size - 1);
}

typedef struct key_value { uint32_t key, value; } key_value;

/* By key, then by index: the order of a stable radix sort of the keys. */
static int by_key(const void *a, const void *b)
{
    const key_value *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return x->value < y->value ? -1 : (x->value > y->value);
}

il_status il_kphoton_map_build(const il_kscene *ks, uint32_t num_emitted, float radius, il_kphoton_map *out,
                               il_error *err)
{
    memset(out, 0, sizeof *out);
    if (num_emitted == 0)
        return il_fail(err, IL_ERR_INVALID, "photon kernel: no photons to emit");
    if (!(radius > 0.0f) || !isfinite(radius))
        return il_fail(err, IL_ERR_INVALID, "photon kernel: the gather radius must be positive (got %g)",
                       (double)radius);
    uint32_t depth = ks->view.max_depth;
    uint64_t n = (uint64_t)num_emitted * depth;
    if (n > INT32_MAX)
        return il_fail(err, IL_ERR_INVALID, "photon kernel: %u photons x %u bounces is more than 2^31 records",
                       num_emitted, depth);
    uint32_t mask = il_kgrid_hash_mask(n);
    ilk_photon *slots = il_malloc(sizeof *slots * n, err);
    key_value *kv = il_malloc(sizeof *kv * n, err);
    out->photons = il_malloc(sizeof *out->photons * n, err);
    out->keys = il_malloc(sizeof *out->keys * n, err);
    out->cell_start = il_calloc((size_t)mask + 1, sizeof *out->cell_start, err);
    out->cell_end = il_calloc((size_t)mask + 1, sizeof *out->cell_end, err);
    if (!slots || !kv || !out->photons || !out->keys || !out->cell_start || !out->cell_end) {
        free(slots);
        free(kv);
        il_kphoton_map_free(out);
        return IL_ERR_MEMORY;
    }
    float cell = ilk_grid_cell_size(radius), inv_cell = 1.0f / cell;
#pragma omp parallel for schedule(dynamic, 256)
    for (uint32_t i = 0; i < num_emitted; i++)
        ilk_photon_trace(&ks->view, i, num_emitted, &slots[(size_t)i * depth]);
    for (uint32_t i = 0; i < (uint32_t)n; i++) {
        kv[i].key = ilk_grid_key(&slots[i], inv_cell, mask);
        kv[i].value = i;
    }
    qsort(kv, n, sizeof *kv, by_key);
    uint32_t stored = 0;
    for (uint32_t i = 0; i < (uint32_t)n; i++) {
        out->keys[i] = kv[i].key;
        out->photons[i] = slots[kv[i].value];
        stored += kv[i].key != ILK_GRID_NO_KEY;
    }
    for (uint32_t i = 0; i < (uint32_t)n; i++)
        ilk_grid_mark(out->keys, (uint32_t)n, i, out->cell_start, out->cell_end);
    free(slots);
    free(kv);
    out->num_slots = n;
    out->grid = ilk_grid_make(out->photons, stored, out->cell_start, out->cell_end, mask, cell);
    return IL_OK;
}

void il_kphoton_map_free(il_kphoton_map *map)
{
    free(map->photons);
    free(map->keys);
    free(map->cell_start);
    free(map->cell_end);
    memset(map, 0, sizeof *map);
}

uint64_t il_kphoton_render(const il_kscene *ks, const il_kphoton_map *map, float radius, uint32_t spp, float *rgb)
{
    const ilk_scene *sc = &ks->view;
    uint32_t n = spp ? spp : 1;
    uint64_t total = 0;
#pragma omp parallel for schedule(dynamic, 4) reduction(+ : total)
    for (uint32_t y = 0; y < sc->height; y++)
        for (uint32_t x = 0; x < sc->width; x++) {
            double acc[3] = {0, 0, 0};
            for (uint32_t s = 0; s < n; s++) {
                uint32_t rays = 0;
                ilk_vec3 L = ilk_photon_pixel_sample(sc, &map->grid, radius, x, y, s, &rays);
                total += rays;
                acc[0] += L.x;
                acc[1] += L.y;
                acc[2] += L.z;
            }
            float *o = &rgb[3 * ((size_t)y * sc->width + x)];
            for (int c = 0; c < 3; c++)
                o[c] = (float)(acc[c] / n);
        }
    return total;
}
