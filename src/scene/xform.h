/* Affine transforms for the loaders: 4x4 row-major in double precision
 * (row 3 is 0 0 0 1), applied to points, vectors and normals. */
#ifndef IL_SCENE_XFORM_H
#define IL_SCENE_XFORM_H

#include "core/vec.h"

typedef struct il_xform { double m[4][4]; } il_xform;

static inline il_xform il_xform_identity(void)
{
    il_xform x = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
    return x;
}

/* a * b: b is applied first. */
static inline il_xform il_xform_mul(const il_xform *a, const il_xform *b)
{
    il_xform r;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++)
                s += a->m[i][k] * b->m[k][j];
            r.m[i][j] = s;
        }
    return r;
}

/* From / to a column-major float[16] (element (row r, column c) at [4c + r]). */
static inline il_xform il_xform_from_cm(const float *t)
{
    il_xform x;
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            x.m[r][c] = t[4 * c + r];
    return x;
}
static inline void il_xform_to_cm(const il_xform *x, float *t)
{
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            t[4 * c + r] = (float)x->m[r][c];
}

static inline il_vec3 il_xform_point(const il_xform *x, double px, double py, double pz)
{
    return v3((float)(x->m[0][0] * px + x->m[0][1] * py + x->m[0][2] * pz + x->m[0][3]),
              (float)(x->m[1][0] * px + x->m[1][1] * py + x->m[1][2] * pz + x->m[1][3]),
              (float)(x->m[2][0] * px + x->m[2][1] * py + x->m[2][2] * pz + x->m[2][3]));
}

static inline il_vec3 il_xform_vector(const il_xform *x, double vx, double vy, double vz)
{
    return v3((float)(x->m[0][0] * vx + x->m[0][1] * vy + x->m[0][2] * vz),
              (float)(x->m[1][0] * vx + x->m[1][1] * vy + x->m[1][2] * vz),
              (float)(x->m[2][0] * vx + x->m[2][1] * vy + x->m[2][2] * vz));
}

/* Determinant of the linear part: negative for a mirroring transform. */
static inline double il_xform_det3(const il_xform *x)
{
    const double(*m)[4] = x->m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* The normal matrix, the inverse transpose of the linear part, computed as the
 * cofactor matrix times sign(det): normals are renormalised afterwards, so the
 * factor |det| does not matter (pbrt-v4, section 3.10.3). */
static inline il_xform il_xform_normal_matrix(const il_xform *x)
{
    const double(*m)[4] = x->m;
    double s = il_xform_det3(x) < 0.0 ? -1.0 : 1.0;
    il_xform n = il_xform_identity();
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            n.m[i][j] = s * (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]);
        }
    return n;
}

#endif
