/* The per-pixel gather of the photon method, shared by the CPU (gcc) and
 * the GPU (src/cuda/photon_kernel.cu, one thread per pixel): a camera ray
 * (the same jittered pinhole ray and Sobol sample as kernel_path.h), its
 * first hit's emission, its direct light by next-event estimation (one
 * emitter by power, a point on it, a shadow ray: kernel_path.h's
 * ilk_direct, as the CPU photon method takes direct light), and the
 * density estimate of the indirect light reflected there from the photons
 * of kernel/kernel_grid.h within the radius (records after a photon's
 * first bounce; Jensen 2001, equation 7.6, with a uniform disc kernel):
 *
 *     L_r(x) = sum_p f_r Phi_p / (pi r^2),   f_r = rho / pi  (Lambertian),
 *
 * keeping only photons on the hit's surface (ilk_photon_on_surface), so
 * light does not leak round corners or through thin walls (Jensen 2001,
 * 7.2). */
#ifndef IL_KERNEL_PHOTON_GATHER_H
#define IL_KERNEL_PHOTON_GATHER_H

#include "kernel/kernel_grid.h"

#define ILK_GATHER_NORMAL_COS 0.9f
/* How far off the hit's tangent plane a photon may lie, in radii, besides
 * the d sin(theta) a curved or faceted surface takes (below). */
#define ILK_GATHER_DISC_THICKNESS 0.1f

/* Whether a photon lies on the surface at p (unit normal n): its normal
 * within ILK_GATHER_NORMAL_COS of n, and off the tangent plane by at most
 * ILK_GATHER_DISC_THICKNESS radii plus d sin(theta), d its distance and
 * theta the turn of its normal from n (a smooth curve, or the next facet
 * of a tessellated one).  Jensen's search sphere compressed along the
 * normal into a disc (Jensen 2001, ch. 7): a floor's photons no longer
 * count the ground's a centimetre beneath it, whose normal agrees.  The
 * CPU photon method's test (methods/photon/pm_internal.h, il_pm_on_surface). */
IL_DEVICE_INLINE bool ilk_photon_on_surface(const ilk_photon *ph, ilk_vec3 p, ilk_vec3 n, float radius)
{
    float c = ilk_dot(ph->n, n);
    if (!(c > ILK_GATHER_NORMAL_COS))
        return false;
    ilk_vec3 o = ilk_sub(ph->p, p);
    float beyond = fabsf(ilk_dot(o, n)) - ILK_GATHER_DISC_THICKNESS * radius;
    return beyond <= 0.0f || beyond * beyond <= (1.0f - c * c) * ilk_dot(o, o);
}

/* Reflected radiance at p (unit normal n facing the viewer, albedo rho). */
IL_DEVICE_INLINE ilk_vec3 ilk_photon_estimate(const ilk_grid *g, ilk_vec3 p, ilk_vec3 n, ilk_vec3 rho, float radius)
{
    ilk_vec3 sum = ilk_v3(0, 0, 0);
    ilk_grid_query q = ilk_grid_query_begin(g, p, radius);
    uint32_t i;
    while (ilk_grid_next(g, &q, &i)) {
        const ilk_photon *ph = &g->photons[i];
        if (ilk_photon_on_surface(ph, p, n, radius))
            sum = ilk_add(sum, ph->power);
    }
    float k = 1.0f / (ILK_PI * ILK_PI * radius * radius);
    return ilk_scale(ilk_mul(sum, rho), k);
}

/* The radiance of one camera sample through pixel (x, y); the rays it
 * casts are added to *rays. */
IL_DEVICE_INLINE ilk_vec3 ilk_photon_pixel_sample(const ilk_scene *sc, const ilk_grid *g, float radius, uint32_t x,
                                                  uint32_t y, uint32_t sample, uint32_t *rays)
{
    ilk_sobol smp = ilk_sobol_start(sc->seed, (uint64_t)y * sc->width + x, sample);
    float u, v;
    ilk_sobol_2d(&smp, &u, &v);
    ilk_ray ray = ilk_camera_ray(&sc->camera, x, y, u, v);
    ilk_hit h;
    ++*rays;
    if (!ilk_bvh_closest(&sc->bvh, &ray, &h))
        return ilk_v3(0, 0, 0);
    const ilk_tri *tr = &sc->bvh.tris[h.tri];
    const ilk_material *m = &sc->materials[tr->pad];
    ilk_vec3 ng = ilk_normalize(ilk_cross(tr->e1, tr->e2));
    float side = ilk_dot(ng, ray.dir);
    ilk_vec3 L = ilk_v3(0, 0, 0);
    if (side < 0.0f || m->two_sided)
        L = m->emission;
    ilk_vec3 n = side < 0.0f ? ng : ilk_scale(ng, -1.0f);
    ilk_vec3 p = ilk_add(ray.org, ilk_scale(ray.dir, h.t));
    ilk_bsdf b;
    b.m = m;
    b.ng = n;
    b.ns = n;
    float ul, unused, u1, u2;
    ilk_sobol_2d(&smp, &ul, &unused);
    ilk_sobol_2d(&smp, &u1, &u2);
    L = ilk_add(L, ilk_direct(sc, &b, p, ilk_scale(ray.dir, -1.0f), ul, u1, u2, false, rays));
    return ilk_add(L, ilk_photon_estimate(g, p, n, m->diffuse, radius));
}

#endif
