/* The CPU side of the shared photon kernels: traces the photons with
 * kernel/kernel_photon.h and builds the hashed grid of kernel/kernel_grid.h
 * over them in the order the GPU builds it (keys, a stable sort by key,
 * cell start/end), and renders the gather of kernel/kernel_photon_gather.h.
 * The reference that the GPU's photon_kernel.cu is compared with. */
#ifndef IL_KERNEL_PHOTON_MAP_H
#define IL_KERNEL_PHOTON_MAP_H

#include "kernel/kernel_grid.h"
#include "kernel/kernel_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The grid's table size for num_slots photon slots: the power of two at or
 * above num_slots / 2, between 2^10 and 2^26 (so the CPU and the GPU hash
 * alike). */
uint32_t il_kgrid_hash_mask(uint64_t num_slots);

typedef struct il_kphoton_map {
    ilk_photon *photons;           /* num_emitted * max_depth slots, sorted by key */
    uint32_t *keys;                /* sorted */
    uint32_t *cell_start, *cell_end;
    uint64_t num_slots;
    ilk_grid grid;                 /* host pointers into the arrays above */
} il_kphoton_map;

/* Traces num_emitted photons through ks (ks->view.max_depth slots each) and
 * builds the grid with cells of side radius.  IL_ERR_INVALID for zero
 * photons, a radius that is not positive and finite, or more slots than the
 * 32-bit indices hold. */
il_status il_kphoton_map_build(const il_kscene *ks, uint32_t num_emitted, float radius, il_kphoton_map *out,
                               il_error *err);
void il_kphoton_map_free(il_kphoton_map *map);

/* The gather into rgb (width x height x 3 floats of ks->view, rows top to
 * bottom): spp jittered camera samples per pixel, averaged.  Returns the
 * rays cast (camera and shadow rays). */
uint64_t il_kphoton_render(const il_kscene *ks, const il_kphoton_map *map, float radius, uint32_t spp, float *rgb);

#ifdef __cplusplus
}
#endif

#endif
