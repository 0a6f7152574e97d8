/* The analytic point-to-polygon form factor, shared by the diffuse methods
 * (radiosity's hemicube tables, hierarchical radiosity's links). */
#ifndef IL_METHODS_FF_ANALYTIC_H
#define IL_METHODS_FF_ANALYTIC_H

#include <stdint.h>
#include "core/vec.h"

/* Lambert's contour integral (Cohen & Wallace, "Radiosity and Realistic
 * Image Synthesis", 1993, eq. 4.14 / Baum et al. 1989): the unoccluded form
 * factor from a differential area at p with unit normal n to the polygon
 * (vertices counter-clockwise seen from its front).  Clips the polygon to
 * the half-space in front of p first. */
double il_ff_point_polygon(il_vec3 p, il_vec3 n, const il_vec3 *poly, uint32_t count);

#endif
