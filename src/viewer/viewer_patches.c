/* The mesh view's patch boundaries (key B, radiosity and hr): the outline
 * of every patch (hr: every element, a leaf of the hierarchy) as orange
 * lines.  A patch is one triangle or a quad split into two, so its outline is
 * its triangles' edges that no other triangle of the same patch shares: the
 * quads' diagonals, which the wireframe (L) draws, are left out.  The patch
 * of each triangle is il_bake_mesh.patches. */
#include <stdlib.h>

#include "cli/cli.h"
#include "viewer/viewer_internal.h"

typedef struct patch_edge {
    uint32_t patch, a, b;             /* a < b: the edge's vertices in its bake mesh */
} patch_edge;

static int edge_order(const void *x, const void *y)
{
    const patch_edge *p = x, *q = y;
    if (p->patch != q->patch)
        return p->patch < q->patch ? -1 : 1;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return p->b < q->b ? -1 : p->b > q->b;
}

void il_view_make_patches(viewer *v)
{
    glGenVertexArrays(1, &v->patch_vao);
    glGenBuffers(1, &v->patch_vbo);
}

/* Appends mesh me's patch outlines to line (2 points, 6 floats per edge)
 * and returns the new count of edges; counts its patches into *patches. */
static size_t mesh_outlines(const il_bake_mesh *me, patch_edge *e, float *line, size_t n,
                            uint32_t *patches)
{
    size_t ne = 0;
    for (uint32_t t = 0; t < me->num_triangles; t++) {
        if (me->patches[t] == UINT32_MAX)     /* mirror/glass: no patch */
            continue;
        const uint32_t *tri = me->indices + 3 * (size_t)t;
        for (int k = 0; k < 3; k++) {
            uint32_t a = tri[k], b = tri[(k + 1) % 3];
            e[ne++] = (patch_edge){me->patches[t], a < b ? a : b, a < b ? b : a};
        }
    }
    qsort(e, ne, sizeof *e, edge_order);
    for (size_t i = 0; i < ne;) {
        size_t j = i + 1;
        while (j < ne && edge_order(&e[i], &e[j]) == 0)
            j++;
        if (i == 0 || e[i].patch != e[i - 1].patch)
            (*patches)++;
        if (j - i == 1)                       /* not shared within the patch */
            for (int k = 0; k < 3; k++) {
                line[n * 6 + k] = me->positions[e[i].a * 3 + k];
                line[n * 6 + 3 + k] = me->positions[e[i].b * 3 + k];
            }
        n += j - i == 1;
        i = j;
    }
    return n;
}

void il_view_upload_patches(viewer *v, const il_bake_result *b)
{
    size_t most = 0, edges = 0;
    for (uint32_t m = 0; m < b->num_meshes; m++) {
        size_t e = (size_t)b->meshes[m].num_triangles * 3;
        edges += e;
        most = e > most ? e : most;
    }
    patch_edge *e = malloc(most * sizeof *e + 1);
    float *line = malloc(edges * 6 * sizeof *line + 1);
    v->patch_vertices = 0;
    v->num_patches = 0;
    if (!e || !line) {
        free(e);
        free(line);
        cli_error("view: out of memory for the patch boundaries");
        return;
    }
    size_t n = 0;
    for (uint32_t m = 0; m < b->num_meshes; m++)
        if (b->meshes[m].patches)
            n = mesh_outlines(&b->meshes[m], e, line, n, &v->num_patches);
    glBindVertexArray(v->patch_vao);
    glBindBuffer(GL_ARRAY_BUFFER, v->patch_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * 6 * sizeof *line), line, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), (void *)0);
    glBindVertexArray(0);
    free(e);
    free(line);
    v->patch_vertices = (GLsizei)(2 * n);
}

/* Over the wireframe where both are on (the depth test passes equal depths). */
void il_view_draw_patches(viewer *v)
{
    if (!v->patch_vertices)
        return;
    glUniform4f(glGetUniformLocation(v->mesh_prog, "line"), 1.0f, 0.55f, 0.1f, 1.0f);
    glDepthFunc(GL_LEQUAL);
    glBindVertexArray(v->patch_vao);
    glDrawArrays(GL_LINES, 0, v->patch_vertices);
    glBindVertexArray(0);
    glDepthFunc(GL_LESS);
}

void il_view_free_patches(viewer *v)
{
    glDeleteVertexArrays(1, &v->patch_vao);
    glDeleteBuffers(1, &v->patch_vbo);
}
