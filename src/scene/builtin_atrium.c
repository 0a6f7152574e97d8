/* The built-in "atrium": a procedurally generated two-storey arcaded courtyard,
 * the large architectural benchmark scene (about 250,000 triangles).
 *
 * Layout (metres, y up): an open courtyard 20 m (x) by 30 m (z) centred on the
 * origin, ringed on both storeys by arcades 4 m deep: columns on the courtyard
 * edge every 2.5 m (8 x 12 bays), round arches between them, a gallery floor
 * with a balustrade on the first storey, a flat roof over the arcades only,
 * solid back walls with doors (ground) and windows (first storey), a tiled
 * floor, and drapes with sinusoidal folds hung in some bays.  Lit by a warm sun
 * through the open roof, a faint uniform sky, and six lamps in the ground
 * arcades.  Fully deterministic (no random numbers).  docs/builtin-scenes.md
 * describes it.
 *
 * Every curved element is a grid of quads (rows x columns of vertices) built
 * by one helper, mesh_grid(): lathed columns and balusters, arch faces and
 * soffits, drapes.  Winding is chosen per quad to agree with the vertex
 * normals, which therefore define the front side. */
#include "scene/builtin.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/vec.h"

/* ---------------------------------------------------------------- layout */

#define AT_HALF_X 10.0f   /* courtyard half-width: the column line at x = +-10 */
#define AT_HALF_Z 15.0f   /* courtyard half-length: the column line at z = +-15 */
#define AT_BAY 2.5f       /* column spacing */
#define AT_DEPTH 4.0f     /* arcade depth, column line to back wall */
#define AT_WALL 0.4f      /* back wall thickness */
#define AT_PANEL 0.5f     /* thickness of the arch panels over the columns */
#define AT_ABACUS 0.33f   /* half-width of the square plinths and abaci */
#define AT_SLAB 0.3f      /* gallery floor / roof thickness */

/* Heights: ground storey columns 0 -> spring line 4.0, arch panels up to the
 * gallery slab (5.4 - 5.7); first storey columns 5.7 -> 9.0, panels up to the
 * roof slab (10.2 - 10.5). */
#define AT_Y_SPRING1 4.0f
#define AT_Y_GALLERY 5.4f
#define AT_Y_FLOOR2 (AT_Y_GALLERY + AT_SLAB)
#define AT_Y_SPRING2 9.0f
#define AT_Y_ROOF 10.2f
#define AT_Y_TOP (AT_Y_ROOF + AT_SLAB)

/* Tessellation, chosen for about 250k triangles in all. */
#define AT_COLUMN_SEGMENTS 28
#define AT_BALUSTER_SEGMENTS 12
#define AT_BALUSTERS_PER_BAY 6
#define AT_ARCH_SEGMENTS 48
#define AT_DRAPE_COLS 72
#define AT_DRAPE_ROWS 40

/* --------------------------------------------------------- mesh building */

/* A growing triangle mesh with per-vertex normals. */
typedef struct mesh_buf {
    float *pos, *nrm;
    uint32_t *idx;
    uint32_t nv, nt, cap_v, cap_t;
    bool failed; /* out of memory: further calls do nothing */
} mesh_buf;

/* Grows *p (capacity *cap elements of `elem` bytes) to hold `need`. */
static bool mesh_grow(void **p, uint32_t *cap, uint32_t need, size_t elem)
{
    if (need <= *cap)
        return true;
    uint32_t c = *cap ? *cap : 4096;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, (size_t)c * elem);
    if (!q)
        return false;
    *p = q;
    *cap = c;
    return true;
}

static uint32_t mesh_vertex(mesh_buf *m, il_vec3 p, il_vec3 n)
{
    if (m->failed)
        return 0;
    /* Positions and normals share one capacity. */
    uint32_t cap_p = m->cap_v, cap_n = m->cap_v;
    if (!mesh_grow((void **)&m->pos, &cap_p, m->nv + 1, 3 * sizeof(float)) ||
        !mesh_grow((void **)&m->nrm, &cap_n, m->nv + 1, 3 * sizeof(float))) {
        m->failed = true;
        return 0;
    }
    m->cap_v = cap_p;
    float *p3 = m->pos + 3 * (size_t)m->nv, *n3 = m->nrm + 3 * (size_t)m->nv;
    p3[0] = p.x, p3[1] = p.y, p3[2] = p.z;
    n3[0] = n.x, n3[1] = n.y, n3[2] = n.z;
    return m->nv++;
}

static void mesh_tri(mesh_buf *m, uint32_t a, uint32_t b, uint32_t c)
{
    if (m->failed)
        return;
    if (!mesh_grow((void **)&m->idx, &m->cap_t, m->nt + 1, 3 * sizeof(uint32_t))) {
        m->failed = true;
        return;
    }
    uint32_t *t = m->idx + 3 * (size_t)m->nt++;
    t[0] = a, t[1] = b, t[2] = c;
}

static il_vec3 mesh_get(const mesh_buf *m, const float *arr, uint32_t v)
{
    return v3(arr[3 * (size_t)v], arr[3 * (size_t)v + 1], arr[3 * (size_t)v + 2]);
}

/* Fills vertex (i, j) of a grid: position and normal (the normal may be left
 * zero when the grid asks for automatic normals). */
typedef void (*grid_fn)(const void *ctx, int i, int j, il_vec3 *p, il_vec3 *n);

/* The shared builder: a grid of (cols+1) x (rows+1) vertices from `fn`, two
 * triangles per cell.  With `auto_normals` the normals are du x dv by central
 * differences over the grid.  Each cell is wound so that its geometric normal
 * agrees with its vertices' normals (the front side). */
static void mesh_grid(mesh_buf *m, int cols, int rows, grid_fn fn, const void *ctx, bool auto_normals)
{
    uint32_t base = m->nv, w = (uint32_t)cols + 1;
    for (int j = 0; j <= rows; j++)
        for (int i = 0; i <= cols; i++) {
            il_vec3 p, n = v3s(0.0f);
            fn(ctx, i, j, &p, &n);
            mesh_vertex(m, p, n);
        }
    if (m->failed)
        return;
#define GRID_P(i, j) mesh_get(m, m->pos, base + (uint32_t)(j) * w + (uint32_t)(i))
    if (auto_normals)
        for (int j = 0; j <= rows; j++)
            for (int i = 0; i <= cols; i++) {
                int i0 = i > 0 ? i - 1 : i, i1 = i < cols ? i + 1 : i;
                int j0 = j > 0 ? j - 1 : j, j1 = j < rows ? j + 1 : j;
                il_vec3 n = v3_normalize(v3_cross(v3_sub(GRID_P(i1, j), GRID_P(i0, j)),
                                                  v3_sub(GRID_P(i, j1), GRID_P(i, j0))));
                float *n3 = m->nrm + 3 * ((size_t)base + (size_t)j * w + (size_t)i);
                n3[0] = n.x, n3[1] = n.y, n3[2] = n.z;
            }
    for (int j = 0; j < rows; j++)
        for (int i = 0; i < cols; i++) {
            uint32_t a = base + (uint32_t)j * w + (uint32_t)i, b = a + 1, c = a + w + 1, d = a + w;
            il_vec3 pa = GRID_P(i, j), pb = GRID_P(i + 1, j), pc = GRID_P(i + 1, j + 1);
            il_vec3 pd = GRID_P(i, j + 1);
            il_vec3 ng = v3_cross(v3_sub(pc, pa), v3_sub(pd, pb));
            il_vec3 ns = v3_add(v3_add(mesh_get(m, m->nrm, a), mesh_get(m, m->nrm, b)),
                                v3_add(mesh_get(m, m->nrm, c), mesh_get(m, m->nrm, d)));
            if (v3_dot(ng, ns) >= 0.0f) {
                mesh_tri(m, a, b, c);
                mesh_tri(m, a, c, d);
            } else {
                mesh_tri(m, a, c, b);
                mesh_tri(m, a, d, c);
            }
        }
#undef GRID_P
}

/* A flat quad p0 p1 p2 p3 (in order around it) facing `n`. */
typedef struct quad_ctx {
    il_vec3 p[4], n;
} quad_ctx;

static void quad_fn(const void *ctx, int i, int j, il_vec3 *p, il_vec3 *n)
{
    const quad_ctx *q = ctx;
    static const int corner[2][2] = {{0, 1}, {3, 2}};
    *p = q->p[corner[j][i]];
    *n = q->n;
}

static void mesh_quad(mesh_buf *m, il_vec3 p0, il_vec3 p1, il_vec3 p2, il_vec3 p3, il_vec3 n)
{
    quad_ctx q = {{p0, p1, p2, p3}, n};
    mesh_grid(m, 1, 1, quad_fn, &q, false);
}

/* An axis-aligned box, all six faces facing out (12 triangles). */
static void mesh_box(mesh_buf *m, il_vec3 lo, il_vec3 hi)
{
    il_vec3 c[8];
    for (int k = 0; k < 8; k++)
        c[k] = v3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
    mesh_quad(m, c[0], c[2], c[6], c[4], v3(-1, 0, 0));
    mesh_quad(m, c[1], c[3], c[7], c[5], v3(1, 0, 0));
    mesh_quad(m, c[0], c[1], c[5], c[4], v3(0, -1, 0));
    mesh_quad(m, c[2], c[3], c[7], c[6], v3(0, 1, 0));
    mesh_quad(m, c[0], c[1], c[3], c[2], v3(0, 0, -1));
    mesh_quad(m, c[4], c[5], c[7], c[6], v3(0, 0, 1));
}

/* A box given by its centre and half extents. */
static void mesh_box_c(mesh_buf *m, il_vec3 c, il_vec3 h)
{
    mesh_box(m, v3_sub(c, h), v3_add(c, h));
}

/* A surface of revolution about the vertical axis through `centre`:
 * profile points (radius, height) from bottom to top. */
typedef struct lathe_ctx {
    il_vec3 centre;
    const float (*prof)[2];
    int np, segments;
} lathe_ctx;

static void lathe_fn(const void *ctx, int i, int j, il_vec3 *p, il_vec3 *n)
{
    const lathe_ctx *l = ctx;
    float phi = (i == l->segments) ? 0.0f : 2.0f * IL_PI * (float)i / (float)l->segments;
    float c = cosf(phi), s = sinf(phi);
    float r = l->prof[j][0], y = l->prof[j][1];
    *p = v3(l->centre.x + r * c, l->centre.y + y, l->centre.z + r * s);
    /* Outward normal of the profile curve: its tangent (dr, dy) turned by -90 degrees. */
    int j0 = j > 0 ? j - 1 : j, j1 = j < l->np - 1 ? j + 1 : j;
    float dr = l->prof[j1][0] - l->prof[j0][0], dy = l->prof[j1][1] - l->prof[j0][1];
    *n = v3_normalize(v3(dy * c, -dr, dy * s));
}

static void mesh_lathe(mesh_buf *m, il_vec3 centre, const float (*prof)[2], int np, int segments)
{
    lathe_ctx l = {centre, prof, np, segments};
    mesh_grid(m, segments, np - 1, lathe_fn, &l, false);
}

/* ---------------------------------------------------------------- frames */

/* One side of the courtyard: the column line starts at `origin` (a corner)
 * and runs along `u` for `bays` bays; `n` points into the courtyard. */
typedef struct side {
    il_vec3 origin, u, n;
    int bays;
} side;

/* A point given in a side's frame: distance along the side, height, and
 * offset towards the courtyard. */
static il_vec3 side_point(const side *s, float along, float y, float in)
{
    return v3(s->origin.x + s->u.x * along + s->n.x * in, y,
              s->origin.z + s->u.z * along + s->n.z * in);
}

/* The four sides, counter-clockwise seen from above: south, east, north, west.
 * n = u x y points into the courtyard. */
static void courtyard_sides(side out[4])
{
    const float hx = AT_HALF_X, hz = AT_HALF_Z;
    int nx = (int)(2.0f * hx / AT_BAY + 0.5f), nz = (int)(2.0f * hz / AT_BAY + 0.5f);
    out[0] = (side){v3(-hx, 0, -hz), v3(1, 0, 0), v3(0, 0, 1), nx};
    out[1] = (side){v3(hx, 0, -hz), v3(0, 0, 1), v3(-1, 0, 0), nz};
    out[2] = (side){v3(hx, 0, hz), v3(-1, 0, 0), v3(0, 0, -1), nx};
    out[3] = (side){v3(-hx, 0, hz), v3(0, 0, -1), v3(1, 0, 0), nz};
}

/* ---------------------------------------------------------------- column */

/* The lathe profile of a column shaft of height h (above its plinth, below
 * its abacus): a torus base, a fillet, a slightly tapering shaft (entasis),
 * an astragal ring and a flaring echinus.  Returns the number of points. */
static int column_profile(float h, float prof[][2])
{
    int n = 0;
    for (int k = 0; k <= 6; k++) { /* torus base, radius 0.07 */
        float a = -0.5f * IL_PI + IL_PI * (float)k / 6.0f;
        prof[n][0] = 0.25f + 0.07f * cosf(a);
        prof[n][1] = 0.07f + 0.07f * sinf(a);
        n++;
    }
    prof[n][0] = 0.215f, prof[n][1] = 0.17f, n++;
    prof[n][0] = 0.205f, prof[n][1] = 0.21f, n++;
    const float shaft0 = 0.22f, shaft1 = h - 0.42f, r_top = 0.175f;
    for (int k = 0; k <= 7; k++) { /* shaft: r = 0.2 - 0.025 t^2 */
        float t = (float)k / 7.0f;
        prof[n][0] = 0.2f - (0.2f - r_top) * t * t;
        prof[n][1] = shaft0 + (shaft1 - shaft0) * t;
        n++;
    }
    for (int k = 1; k <= 5; k++) { /* astragal: half torus, radius 0.025 */
        float a = -0.5f * IL_PI + IL_PI * (float)k / 6.0f;
        prof[n][0] = r_top + 0.025f * cosf(a);
        prof[n][1] = shaft1 + 0.025f + 0.025f * sinf(a);
        n++;
    }
    for (int k = 0; k <= 5; k++) { /* echinus: quadratic flare to 0.31 */
        float s = (float)k / 5.0f;
        prof[n][0] = r_top + (0.31f - r_top) * (1.0f - (1.0f - s) * (1.0f - s));
        prof[n][1] = shaft1 + 0.07f + (h - shaft1 - 0.07f) * s;
        n++;
    }
    return n;
}

/* A column standing at `base` (centre of its foot) whose abacus top is at
 * height y_top: square plinth, lathed shaft, square abacus. */
static void add_column(mesh_buf *m, il_vec3 base, float y_top)
{
    const float plinth = 0.25f, abacus = 0.12f;
    mesh_box(m, v3(base.x - AT_ABACUS, base.y, base.z - AT_ABACUS),
             v3(base.x + AT_ABACUS, base.y + plinth, base.z + AT_ABACUS));
    mesh_box(m, v3(base.x - AT_ABACUS, y_top - abacus, base.z - AT_ABACUS),
             v3(base.x + AT_ABACUS, y_top, base.z + AT_ABACUS));
    float prof[40][2];
    int np = column_profile(y_top - abacus - base.y - plinth, prof);
    mesh_lathe(m, v3(base.x, base.y + plinth, base.z), (const float(*)[2])prof, np, AT_COLUMN_SEGMENTS);
}

/* ----------------------------------------------------------------- arch */

/* One arch panel: the wall between two columns, from the spring line y_s up
 * to y_t, `AT_PANEL` thick, pierced by a semicircular arch of radius r
 * centred at the middle of the bay on the spring line. */
typedef struct arch_ctx {
    const side *s;
    float along0;          /* the bay's start along the side */
    float ys, yt, r;
    float theta[AT_ARCH_SEGMENTS + 1]; /* from pi (left) down to 0 (right) */
    float in;              /* face offset (faces), or unused (soffit) */
    int face;              /* +1 front (courtyard), -1 back, 0 soffit */
} arch_ctx;

/* The point where the ray from the arch centre at angle theta leaves the
 * panel's rectangle [0, bay] x [ys, yt] (in along/height coordinates). */
static void arch_outer(const arch_ctx *a, float theta, float *u, float *y)
{
    float half = 0.5f * AT_BAY, c = cosf(theta), s = sinf(theta);
    float theta_l = atan2f(a->yt - a->ys, -half), theta_r = atan2f(a->yt - a->ys, half);
    if (theta >= theta_l) {        /* left edge */
        *u = 0.0f;
        *y = a->ys + half * s / -c;
    } else if (theta <= theta_r) { /* right edge */
        *u = AT_BAY;
        *y = a->ys + half * s / c;
    } else {                       /* top edge */
        *u = half + (a->yt - a->ys) * c / s;
        *y = a->yt;
    }
}

static void arch_face_fn(const void *ctx, int i, int j, il_vec3 *p, il_vec3 *n)
{
    const arch_ctx *a = ctx;
    float t = a->theta[i], u, y;
    if (j == 0) {
        u = 0.5f * AT_BAY + a->r * cosf(t);
        y = a->ys + a->r * sinf(t);
    } else {
        arch_outer(a, t, &u, &y);
    }
    *p = side_point(a->s, a->along0 + u, y, a->in);
    *n = v3_scale(a->s->n, (float)a->face);
}

static void arch_soffit_fn(const void *ctx, int i, int j, il_vec3 *p, il_vec3 *n)
{
    const arch_ctx *a = ctx;
    float t = a->theta[i], c = cosf(t), s = sinf(t);
    float in = j == 0 ? -0.5f * AT_PANEL : 0.5f * AT_PANEL;
    *p = side_point(a->s, a->along0 + 0.5f * AT_BAY + a->r * c, a->ys + a->r * s, in);
    /* Towards the arch's centre line. */
    *n = v3(-c * a->s->u.x, -s, -c * a->s->u.z);
}

static void add_arch(mesh_buf *m, const side *s, int bay, float ys, float yt)
{
    arch_ctx a = {.s = s, .along0 = AT_BAY * (float)bay, .ys = ys, .yt = yt};
    a.r = 0.5f * AT_BAY - AT_ABACUS;
    /* Angles: a third of the segments on each of the rectangle's left, top and
     * right edges, so that the outer outline passes through both corners. */
    float half = 0.5f * AT_BAY;
    float theta_l = atan2f(yt - ys, -half), theta_r = atan2f(yt - ys, half);
    const int k = AT_ARCH_SEGMENTS / 3;
    for (int i = 0; i <= AT_ARCH_SEGMENTS; i++) {
        float t;
        if (i <= k)
            t = IL_PI + (theta_l - IL_PI) * (float)i / (float)k;
        else if (i <= 2 * k)
            t = theta_l + (theta_r - theta_l) * (float)(i - k) / (float)k;
        else
            t = theta_r * (1.0f - (float)(i - 2 * k) / (float)(AT_ARCH_SEGMENTS - 2 * k));
        a.theta[i] = t;
    }
    a.face = 1;
    a.in = 0.5f * AT_PANEL;
    mesh_grid(m, AT_ARCH_SEGMENTS, 1, arch_face_fn, &a, false);
    a.face = -1;
    a.in = -0.5f * AT_PANEL;
    mesh_grid(m, AT_ARCH_SEGMENTS, 1, arch_face_fn, &a, false);
    mesh_grid(m, AT_ARCH_SEGMENTS, 1, arch_soffit_fn, &a, false);
}

/* ------------------------------------------------------------ balustrade */

static const float baluster_profile[10][2] = {
    {0.050f, 0.00f}, {0.060f, 0.04f}, {0.045f, 0.10f}, {0.040f, 0.20f}, {0.070f, 0.35f},
    {0.075f, 0.45f}, {0.050f, 0.60f}, {0.035f, 0.68f}, {0.050f, 0.74f}, {0.060f, 0.80f},
};

/* Bottom rail, balusters and hand rail across one bay of the gallery. */
static void add_balustrade(mesh_buf *m, const side *s, int bay, float y0)
{
    const float start = AT_BAY * (float)bay + AT_ABACUS, len = AT_BAY - 2.0f * AT_ABACUS;
    const float rail = 0.12f, post = 0.80f;
    il_vec3 a = side_point(s, start, y0, -0.15f), b = side_point(s, start + len, y0 + rail, 0.15f);
    mesh_box(m, v3_min(a, b), v3_max(a, b));
    a = side_point(s, start, y0 + rail + post, -0.17f);
    b = side_point(s, start + len, y0 + 2.0f * rail + post, 0.17f);
    mesh_box(m, v3_min(a, b), v3_max(a, b));
    for (int k = 0; k < AT_BALUSTERS_PER_BAY; k++) {
        float along = start + len * ((float)k + 0.5f) / (float)AT_BALUSTERS_PER_BAY;
        mesh_lathe(m, side_point(s, along, y0 + rail, 0.0f), baluster_profile, 10,
                   AT_BALUSTER_SEGMENTS);
    }
}

/* ----------------------------------------------------------------- drape */

/* Cloth hanging from a rod: across the bay u, down the drop v; folds are a
 * sine across the width whose depth grows towards the hem, and the hem
 * swings a little. */
typedef struct drape_ctx {
    const side *s;
    float along0, width, y_top, drop, in;
    float folds, phase;
} drape_ctx;

static void drape_fn(const void *ctx, int i, int j, il_vec3 *p, il_vec3 *n)
{
    const drape_ctx *d = ctx;
    float u = (float)i / AT_DRAPE_COLS, v = (float)j / AT_DRAPE_ROWS;
    float depth = 0.03f + 0.08f * v;
    float off = depth * sinf(2.0f * IL_PI * d->folds * u + d->phase) + 0.05f * v * v * sinf(IL_PI * u);
    *p = side_point(d->s, d->along0 + d->width * u, d->y_top - d->drop * v, d->in + off);
    (void)n; /* automatic normals */
}

static void add_drape(mesh_buf *cloth, mesh_buf *metal, const side *s, int bay, float y_top,
                      float drop, float in, float phase)
{
    const float gap = AT_ABACUS + 0.03f;
    drape_ctx d = {s, AT_BAY * (float)bay + gap, AT_BAY - 2.0f * gap, y_top, drop, in, 6.0f, phase};
    mesh_grid(cloth, AT_DRAPE_COLS, AT_DRAPE_ROWS, drape_fn, &d, true);
    /* The rod it hangs from, between the capitals. */
    il_vec3 a = side_point(s, AT_BAY * (float)bay + AT_ABACUS, y_top + 0.01f, in - 0.02f);
    il_vec3 b = side_point(s, AT_BAY * (float)(bay + 1) - AT_ABACUS, y_top + 0.05f, in + 0.02f);
    mesh_box(metal, v3_min(a, b), v3_max(a, b));
}

/* --------------------------------------------------------- slabs, walls */

/* A horizontal slab over the arcade ring between the back walls and the
 * courtyard edge (flush with the arch panels), from y0 to y1. */
static void add_ring_slab(mesh_buf *m, float y0, float y1)
{
    const float ox = AT_HALF_X + AT_DEPTH, oz = AT_HALF_Z + AT_DEPTH;
    const float ix = AT_HALF_X - 0.5f * AT_PANEL, iz = AT_HALF_Z - 0.5f * AT_PANEL;
    mesh_box(m, v3(-ox, y0, -oz), v3(ox, y1, -iz));
    mesh_box(m, v3(-ox, y0, iz), v3(ox, y1, oz));
    mesh_box(m, v3(-ox, y0, -iz), v3(-ix, y1, iz));
    mesh_box(m, v3(ix, y0, -iz), v3(ox, y1, iz));
}

static void add_back_walls(mesh_buf *m)
{
    const float ox = AT_HALF_X + AT_DEPTH, oz = AT_HALF_Z + AT_DEPTH, t = AT_WALL;
    mesh_box(m, v3(-ox - t, 0, -oz - t), v3(ox + t, AT_Y_TOP, -oz));
    mesh_box(m, v3(-ox - t, 0, oz), v3(ox + t, AT_Y_TOP, oz + t));
    mesh_box(m, v3(-ox - t, 0, -oz), v3(-ox, AT_Y_TOP, oz));
    mesh_box(m, v3(ox, 0, -oz), v3(ox + t, AT_Y_TOP, oz));
}

/* A door in every other bay of the ground storey and a window in every bay of
 * the first, as thin panels standing proud of the back walls. */
static void add_openings(mesh_buf *wood, mesh_buf *glass, const side *s)
{
    const float wall_in = -AT_DEPTH; /* the back wall's face, in the side's frame */
    for (int b = 0; b < s->bays; b++) {
        float mid = AT_BAY * ((float)b + 0.5f);
        if (b % 2 == 1) {
            il_vec3 lo = side_point(s, mid - 0.6f, 0.0f, wall_in);
            il_vec3 hi = side_point(s, mid + 0.6f, 2.4f, wall_in + 0.05f);
            mesh_box(wood, v3_min(lo, hi), v3_max(lo, hi));
        }
        il_vec3 lo = side_point(s, mid - 0.5f, AT_Y_FLOOR2 + 1.0f, wall_in);
        il_vec3 hi = side_point(s, mid + 0.5f, AT_Y_FLOOR2 + 2.6f, wall_in + 0.03f);
        mesh_box(glass, v3_min(lo, hi), v3_max(lo, hi));
    }
}

/* ----------------------------------------------------------------- floor */

/* Ground over the whole plan (dark grout) with square tiles, 1 m pitch and
 * 2 cm joints, in a checkerboard of two stones. */
static void add_floor(mesh_buf *grout, mesh_buf *tile_a, mesh_buf *tile_b)
{
    const float ox = AT_HALF_X + AT_DEPTH, oz = AT_HALF_Z + AT_DEPTH;
    const il_vec3 up = v3(0, 1, 0);
    mesh_quad(grout, v3(-ox, 0, -oz), v3(ox, 0, -oz), v3(ox, 0, oz), v3(-ox, 0, oz), up);
    const float pitch = 1.0f, joint = 0.02f, y = 0.005f;
    int nx = (int)(2.0f * ox / pitch + 0.5f), nz = (int)(2.0f * oz / pitch + 0.5f);
    for (int j = 0; j < nz; j++)
        for (int i = 0; i < nx; i++) {
            float x0 = -ox + pitch * (float)i + 0.5f * joint, x1 = x0 + pitch - joint;
            float z0 = -oz + pitch * (float)j + 0.5f * joint, z1 = z0 + pitch - joint;
            mesh_quad((i + j) % 2 ? tile_b : tile_a, v3(x0, y, z0), v3(x1, y, z0), v3(x1, y, z1),
                      v3(x0, y, z1), up);
        }
}

/* ------------------------------------------------------------- lamps */

/* A lamp hanging in the middle of an arcade walkway: a point light with a
 * metal canopy above it on a rod from the gallery slab. */
static il_status add_lamp(il_scene *scene, mesh_buf *metal, const side *s, float along, il_error *err)
{
    const float y = AT_Y_GALLERY - 1.0f;
    il_vec3 p = side_point(s, along, y, -0.5f * AT_DEPTH);
    mesh_box_c(metal, v3(p.x, y + 0.17f, p.z), v3(0.15f, 0.02f, 0.15f));
    mesh_box_c(metal, v3(p.x, 0.5f * (y + 0.19f + AT_Y_GALLERY), p.z),
               v3(0.012f, 0.5f * (AT_Y_GALLERY - y - 0.19f), 0.012f));
    /* Warm light (about 2700 K), intensity in W/sr. */
    il_light_desc l = {.type = IL_LIGHT_POINT, .position = p, .intensity = v3(12.0f, 8.5f, 4.5f)};
    return il_scene_add_light(scene, &l, err);
}

/* -------------------------------------------------------------- scene */

enum { M_STONE, M_TILE_A, M_TILE_B, M_GROUT, M_RED, M_BLUE, M_GREEN, M_WOOD, M_GLASS, M_METAL, M_COUNT };

static const il_material_desc atrium_materials[M_COUNT] = {
    {.name = "stone", .type = IL_MATERIAL_DIFFUSE, .diffuse = {0.72f, 0.66f, 0.55f}},
    {.name = "floor_marble", .type = IL_MATERIAL_PHONG, .diffuse = {0.66f, 0.62f, 0.55f},
     .specular = {0.04f, 0.04f, 0.04f}, .exponent = 200.0f},
    {.name = "floor_terracotta", .type = IL_MATERIAL_PHONG, .diffuse = {0.42f, 0.22f, 0.14f},
     .specular = {0.04f, 0.04f, 0.04f}, .exponent = 200.0f},
    {.name = "grout", .type = IL_MATERIAL_DIFFUSE, .diffuse = {0.2f, 0.2f, 0.19f}},
    {.name = "drape_red", .type = IL_MATERIAL_DIFFUSE, .diffuse = {0.55f, 0.06f, 0.05f}},
    {.name = "drape_blue", .type = IL_MATERIAL_DIFFUSE, .diffuse = {0.06f, 0.10f, 0.45f}},
    {.name = "drape_green", .type = IL_MATERIAL_DIFFUSE, .diffuse = {0.07f, 0.38f, 0.10f}},
    {.name = "wood", .type = IL_MATERIAL_DIFFUSE, .diffuse = {0.25f, 0.14f, 0.07f}},
    {.name = "window", .type = IL_MATERIAL_PHONG, .diffuse = {0.03f, 0.04f, 0.05f},
     .specular = {0.3f, 0.3f, 0.3f}, .exponent = 400.0f},
    {.name = "brass", .type = IL_MATERIAL_PHONG, .diffuse = {0.05f, 0.04f, 0.02f},
     .specular = {0.6f, 0.45f, 0.2f}, .exponent = 60.0f},
};

/* Bays that carry drapes: (side, bay, storey), colours cycling red, blue, green. */
static const int atrium_drapes[][3] = {
    {1, 2, 0}, {1, 7, 0}, {3, 4, 0}, {3, 9, 0}, {1, 4, 1}, {1, 10, 1}, {3, 1, 1}, {3, 7, 1},
};

static void build_geometry(mesh_buf mb[M_COUNT])
{
    side sides[4];
    courtyard_sides(sides);
    for (int k = 0; k < 4; k++) {
        const side *s = &sides[k];
        for (int b = 0; b < s->bays; b++) {
            il_vec3 foot = side_point(s, AT_BAY * (float)b, 0.0f, 0.0f);
            add_column(&mb[M_STONE], foot, AT_Y_SPRING1);
            add_column(&mb[M_STONE], v3(foot.x, AT_Y_FLOOR2, foot.z), AT_Y_SPRING2);
            add_arch(&mb[M_STONE], s, b, AT_Y_SPRING1, AT_Y_GALLERY);
            add_arch(&mb[M_STONE], s, b, AT_Y_SPRING2, AT_Y_ROOF);
            add_balustrade(&mb[M_STONE], s, b, AT_Y_FLOOR2);
        }
        /* Fill the outer quarter at each corner where two panels meet. */
        il_vec3 c = side_point(s, 0.0f, 0.0f, 0.0f);
        il_vec3 h = v3(0.5f * AT_PANEL, 0.0f, 0.5f * AT_PANEL);
        mesh_box(&mb[M_STONE], v3(c.x - h.x, AT_Y_SPRING1, c.z - h.z), v3(c.x + h.x, AT_Y_GALLERY, c.z + h.z));
        mesh_box(&mb[M_STONE], v3(c.x - h.x, AT_Y_SPRING2, c.z - h.z), v3(c.x + h.x, AT_Y_ROOF, c.z + h.z));
        add_openings(&mb[M_WOOD], &mb[M_GLASS], s);
    }
    add_ring_slab(&mb[M_STONE], AT_Y_GALLERY, AT_Y_FLOOR2);
    add_ring_slab(&mb[M_STONE], AT_Y_ROOF, AT_Y_TOP);
    add_back_walls(&mb[M_STONE]);
    add_floor(&mb[M_GROUT], &mb[M_TILE_A], &mb[M_TILE_B]);

    const size_t nd = sizeof atrium_drapes / sizeof atrium_drapes[0];
    for (size_t i = 0; i < nd; i++) {
        const side *s = &sides[atrium_drapes[i][0]];
        int bay = atrium_drapes[i][1];
        mesh_buf *cloth = &mb[M_RED + (int)(i % 3)];
        float phase = 0.7f * (float)i;
        if (atrium_drapes[i][2] == 0) /* ground storey: on the column line, 1 m above the floor */
            add_drape(cloth, &mb[M_METAL], s, bay, AT_Y_SPRING1 - 0.1f, AT_Y_SPRING1 - 1.1f, 0.0f, phase);
        else /* first storey: just behind the balustrade, down to the gallery floor */
            add_drape(cloth, &mb[M_METAL], s, bay, AT_Y_SPRING2 - 0.1f,
                      AT_Y_SPRING2 - 0.1f - AT_Y_FLOOR2 - 0.3f, -0.45f, phase);
    }
}

il_status il_builtin_atrium(il_scene *scene, il_error *err)
{
    mesh_buf mb[M_COUNT];
    memset(mb, 0, sizeof mb);
    build_geometry(mb);

    il_status st = IL_OK;
    side sides[4];
    courtyard_sides(sides);
    /* Lamps: two along each long arcade, one along each short one. */
    const float lamp_at[4][2] = {{0.5f, -1.0f}, {0.25f, 0.75f}, {0.5f, -1.0f}, {0.25f, 0.75f}};
    for (int k = 0; k < 4 && st == IL_OK; k++)
        for (int q = 0; q < 2 && st == IL_OK; q++)
            if (lamp_at[k][q] >= 0.0f)
                st = add_lamp(scene, &mb[M_METAL], &sides[k],
                              lamp_at[k][q] * AT_BAY * (float)sides[k].bays, err);
    for (int k = 0; k < M_COUNT && st == IL_OK; k++)
        if (mb[k].failed)
            st = il_fail(err, IL_ERR_MEMORY, "atrium: out of memory building the geometry");

    for (int k = 0; k < M_COUNT && st == IL_OK; k++) {
        uint32_t mat;
        st = il_scene_add_material(scene, &atrium_materials[k], &mat, err);
        if (st != IL_OK || mb[k].nt == 0)
            continue;
        il_mesh_desc md = {
            .name = atrium_materials[k].name,
            .num_vertices = mb[k].nv,
            .num_triangles = mb[k].nt,
            .positions = mb[k].pos,
            .normals = mb[k].nrm,
            .indices = mb[k].idx,
            .material = mat,
        };
        st = il_scene_add_mesh(scene, &md, err);
    }
    for (int k = 0; k < M_COUNT; k++) {
        free(mb[k].pos);
        free(mb[k].nrm);
        free(mb[k].idx);
    }
    if (st != IL_OK)
        return st;

    /* Sun: warm (about 5000 K), 10.5 W/m^2 on a surface facing it, 53 degrees
     * high, shining from the south-west over the camera's shoulder. */
    il_light_desc sun = {
        .type = IL_LIGHT_DIRECTIONAL,
        .direction = v3_normalize(v3(0.35f, -0.8f, 0.5f)),
        .intensity = v3(11.0f, 10.2f, 8.6f),
    };
    if ((st = il_scene_add_light(scene, &sun, err)) != IL_OK)
        return st;
    /* A faint blue sky through the open roof. */
    il_environment_desc sky = {.radiance = v3(0.25f, 0.35f, 0.55f)};
    if ((st = il_scene_set_environment(scene, &sky, err)) != IL_OK)
        return st;

    /* Standing in the south end of the courtyard at eye height, looking
     * along its length. */
    il_camera_desc cam = {
        .position = v3(0.0f, 1.7f, -AT_HALF_Z + 1.5f),
        .target = v3(0.0f, 3.2f, AT_HALF_Z),
        .up = v3(0.0f, 1.0f, 0.0f),
        .fov_y = 60.0f,
    };
    return il_scene_set_camera(scene, &cam, err);
}
