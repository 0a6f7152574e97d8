/* Thin-pane optics; see pane.h and docs/materials.md. */
#include "scene/pane.h"

#include <math.h>

/* r < 1 (r = 1 only at grazing incidence, where all is reflected). */
static double slab_t(double r, double tau)
{
    return r < 1.0 ? (1.0 - r) * (1.0 - r) * tau / (1.0 - r * r * tau * tau) : 0.0;
}

static double slab_r(double r, double tau)
{
    return r < 1.0 ? r + (1.0 - r) * (1.0 - r) * r * tau * tau / (1.0 - r * r * tau * tau) : 1.0;
}

void il_pane_optics(float ior, float tau0, float cos_i, float *reflectance, float *transmittance)
{
    double n = ior, ci = cos_i > 0.0f ? (cos_i < 1.0f ? cos_i : 1.0f) : 0.0;
    double sin2_t = (1.0 - ci * ci) / (n * n);          /* Snell's law, into the glass */
    double ct = sqrt(1.0 - sin2_t);
    /* Fresnel amplitude ratios of the air-glass face (the glass-air face
     * reflects the same fractions). */
    double rs = (ci - n * ct) / (ci + n * ct), rp = (n * ci - ct) / (n * ci + ct);
    rs *= rs;
    rp *= rp;
    double tau = tau0 >= 1.0f ? 1.0 : tau0 > 0.0f ? pow(tau0, 1.0 / ct) : 0.0;
    *reflectance = (float)(0.5 * (slab_r(rs, tau) + slab_r(rp, tau)));
    *transmittance = (float)(0.5 * (slab_t(rs, tau) + slab_t(rp, tau)));
}

static double normal_reflectance(double n)
{
    double f = (n - 1.0) / (n + 1.0);
    return f * f;
}

float il_pane_clear_transmittance(float ior)
{
    double f0 = normal_reflectance(ior);
    return (float)((1.0 - f0) / (1.0 + f0));
}

float il_pane_tau_for(float ior, float t)
{
    double f0 = normal_reflectance(ior), a = (1.0 - f0) * (1.0 - f0);
    if (!(t > 0.0f))
        return 0.0f;
    /* The positive root, written without the cancellation of -a + sqrt(...). */
    double tau = 2.0 * t / (a + sqrt(a * a + 4.0 * (double)t * t * f0 * f0));
    return tau < 1.0 ? (float)tau : 1.0f;
}
