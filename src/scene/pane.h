/* Optics of a thin pane of glass (IL_MATERIAL_THIN_GLASS): a slab of index
 * n whose thickness is negligible next to the scene, so light passes it
 * along a straight line.  Reflectance and transmittance sum the slab's
 * incoherent inter-reflections per polarisation (Born & Wolf, Principles of
 * Optics, 1.6; the same model as Radiance's `glass` material):
 *
 *     T_k = (1 - r_k)^2 tau / (1 - r_k^2 tau^2)
 *     R_k = r_k + (1 - r_k)^2 r_k tau^2 / (1 - r_k^2 tau^2)
 *
 * with r_k the Fresnel reflectance of one face for polarisation k (s, p),
 * tau = tau0^(1 / cos theta_t) the glass's internal transmittance along the
 * refracted path, and R, T the means over the two polarisations. */
#ifndef IL_SCENE_PANE_H
#define IL_SCENE_PANE_H

/* R and T of a pane of index ior > 1 and internal transmittance tau0 (per
 * normal pass through the glass, 0 to 1) for light arriving at cos_i (0 to 1)
 * from either side. */
void il_pane_optics(float ior, float tau0, float cos_i, float *reflectance, float *transmittance);

/* The light transmittance at normal incidence of a clear pane (tau0 = 1):
 * (1 - F0) / (1 + F0), F0 = ((ior - 1) / (ior + 1))^2; 0.923 at ior 1.5. */
float il_pane_clear_transmittance(float ior);

/* The tau0 that gives a pane of index ior the transmittance t at normal
 * incidence, 0 < t <= il_pane_clear_transmittance(ior) (the root of the
 * quadratic t F0^2 tau^2 + (1 - F0)^2 tau - t = 0). */
float il_pane_tau_for(float ior, float t);

#endif
