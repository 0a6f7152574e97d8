/* The radiosity and hr mesh view: the baked per-vertex radiance drawn by
 * OpenGL as a Gouraud-shaded mesh from any camera, with the debugging views
 * on request: the triangle edges (L), the patch boundaries (B,
 * viewer_patches.c) and the vertex normals (N) as short lines, and the
 * environment behind it (viewer_background.c; docs/viewer.md). */
#include <math.h>
#include <stdlib.h>

#include "cli/cli.h"
#include "viewer/viewer_internal.h"

bool il_view_make_mesh_program(viewer *v)
{
    static const char *vs =
        "#version 330 core\n"
        "layout(location = 0) in vec3 position;\n"
        "layout(location = 1) in vec3 radiance;\n"
        "layout(location = 2) in float kind;\n"
        "uniform mat4 mvp;\n"
        "out vec3 L;\n"
        "flat out float K;\n"
        "void main() { L = radiance; K = kind; gl_Position = mvp * vec4(position, 1.0); }\n";
    /* Radiance * 2^EV into layer 0, its alpha the kind of surface (1: a
     * patch, 0.5: mirror/glass, 0: none drawn); a debugging line's colour
     * into layer 1. */
    static const char *fs =
        "#version 330 core\n"
        "in vec3 L;\n"
        "flat in float K;\n"
        "layout(location = 0) out vec4 radiance;\n"
        "layout(location = 1) out vec4 lines;\n"
        "uniform float scale;\n"
        "uniform vec4 line;\n"
        "void main() {\n"
        "    radiance = vec4(L * scale, K);\n"
        "    lines = line;\n"
        "}\n";
    /* The render's box filter: the mean radiance of the S x S samples of a
     * pixel, then the linear operator (clamped, IEC 61966-2-1 sRGB), as
     * il_tonemap maps a film's pixel; a line in any sample covers the pixel.
     * A sample that no triangle covered (alpha 0) takes the environment's
     * radiance through the pixel's centre (viewer_background.c), one on a
     * mirror or glass triangle the path-traced layer's pixel
     * (viewer_layer.c; black until the camera rests). */
    static const char *rvs =
        "#version 330 core\n"
        "void main() {\n"
        "    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
        "    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
        "}\n";
    static const char *rfs =
        "#version 330 core\n"
        "out vec4 color;\n"
        "uniform sampler2D radiance;\n"
        "uniform sampler2D lines;\n"
        "uniform int ss;\n"
        "uniform sampler2D background;\n"
        "uniform int has_background;\n"
        "uniform float scale;\n"
        "uniform vec2 size;\n"
        "uniform sampler2D layer;\n"
        "uniform int has_layer;\n"
        "void main() {\n"
        "    ivec2 base = ivec2(gl_FragCoord.xy) * ss;\n"
        "    vec2 uv = vec2(gl_FragCoord.x / size.x, 1.0 - gl_FragCoord.y / size.y);\n"
        "    vec3 bg = vec3(0.0), spec = vec3(0.0);\n"
        "    if (has_background != 0)\n"
        "        bg = scale * texture(background, uv).rgb;\n"
        "    if (has_layer != 0)\n"
        "        spec = scale * texture(layer, uv).rgb;\n"
        "    vec3 sum = vec3(0.0);\n"
        "    vec4 line = vec4(0.0);\n"
        "    for (int y = 0; y < ss; y++)\n"
        "        for (int x = 0; x < ss; x++) {\n"
        "            vec4 r = texelFetch(radiance, base + ivec2(x, y), 0);\n"
        "            /* no triangle: the environment; mirror/glass: the path tracer's */\n"
        "            sum += r.a == 0.0 ? bg : r.a < 0.75 ? spec : r.rgb;\n"
        "            vec4 l = texelFetch(lines, base + ivec2(x, y), 0);\n"
        "            if (l.a > line.a) line = l;\n"
        "        }\n"
        "    if (line.a > 0.0) { color = vec4(line.rgb, 1.0); return; }\n"
        "    vec3 c = clamp(sum / float(ss * ss), 0.0, 1.0);\n"
        "    vec3 s = mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055,\n"
        "                 step(vec3(0.0031308), c));\n"
        "    color = vec4(s, 1.0);\n"
        "}\n";
    GLuint a = il_view_compile(GL_VERTEX_SHADER, vs), b = il_view_compile(GL_FRAGMENT_SHADER, fs);
    if (!a || !b)
        return false;
    v->mesh_prog = glCreateProgram();
    glAttachShader(v->mesh_prog, a);
    glAttachShader(v->mesh_prog, b);
    glLinkProgram(v->mesh_prog);
    glDeleteShader(a);
    glDeleteShader(b);
    GLint ok = 0;
    glGetProgramiv(v->mesh_prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        cli_error("view: the mesh shader program does not link");
        return false;
    }
    glGenVertexArrays(1, &v->mesh_vao);
    glGenBuffers(1, &v->mesh_vbo);
    glGenBuffers(1, &v->mesh_ibo);
    glGenVertexArrays(1, &v->normal_vao);
    glGenBuffers(1, &v->normal_vbo);
    il_view_make_patches(v);

    a = il_view_compile(GL_VERTEX_SHADER, rvs);
    b = il_view_compile(GL_FRAGMENT_SHADER, rfs);
    if (!a || !b)
        return false;
    v->resolve_prog = glCreateProgram();
    glAttachShader(v->resolve_prog, a);
    glAttachShader(v->resolve_prog, b);
    glLinkProgram(v->resolve_prog);
    glDeleteShader(a);
    glDeleteShader(b);
    glGetProgramiv(v->resolve_prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        cli_error("view: the mesh resolve program does not link");
        return false;
    }
    glGenVertexArrays(1, &v->resolve_vao);
    glGenFramebuffers(1, &v->ss_fbo);
    glGenTextures(1, &v->ss_radiance);
    glGenTextures(1, &v->ss_lines);
    glGenRenderbuffers(1, &v->ss_depth);
    return true;
}

/* Samples per pixel side: 4 (16 per pixel, like the renders' 4 to 16 spp),
 * fewer when the window is larger than 1024 pixels, and 1 while the camera
 * moves (the preview: 16 times fewer fragments keep the frame rate up). */
static int ss_factor(int fw, int fh)
{
    int m = fw > fh ? fw : fh;
    return m <= 1024 ? 4 : m <= 2048 ? 2 : 1;
}

/* (Re)allocates the supersampled framebuffer for a fw x fh window. */
static bool ss_resize(viewer *v, int w, int h)
{
    if (v->ss_w == w && v->ss_h == h)
        return true;
    glBindTexture(GL_TEXTURE_2D, v->ss_radiance);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, w, h, 0, GL_RGBA, GL_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, v->ss_lines);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindRenderbuffer(GL_RENDERBUFFER, v->ss_depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, v->ss_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, v->ss_radiance, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, v->ss_lines, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, v->ss_depth);
    static const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, bufs);
    bool ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (!ok) {
        cli_error("view: the mesh framebuffer (%d x %d) is incomplete", w, h);
        return false;
    }
    v->ss_w = w;
    v->ss_h = h;
    return true;
}

/* The vertex normals as lines from each vertex, 3% of the mesh's bounding
 * box diagonal long. */
static void upload_normals(viewer *v, const il_bake_result *b, size_t nv)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t m = 0; m < b->num_meshes; m++)
        for (size_t i = 0; i < (size_t)b->meshes[m].num_vertices * 3; i++) {
            float x = b->meshes[m].positions[i];
            lo[i % 3] = fminf(lo[i % 3], x);
            hi[i % 3] = fmaxf(hi[i % 3], x);
        }
    float d2 = 0.0f;
    for (int k = 0; k < 3; k++)
        d2 += nv ? (hi[k] - lo[k]) * (hi[k] - lo[k]) : 0.0f;
    float len = 0.03f * sqrtf(d2);
    float *line = malloc(nv * 6 * sizeof *line + 1);
    if (!line) {
        v->normal_vertices = 0;
        return;
    }
    size_t j = 0;
    for (uint32_t m = 0; m < b->num_meshes; m++) {
        const il_bake_mesh *me = &b->meshes[m];
        for (uint32_t i = 0; i < me->num_vertices; i++, j++)
            for (int k = 0; k < 3; k++) {
                line[j * 6 + k] = me->positions[i * 3 + k];
                line[j * 6 + 3 + k] = me->positions[i * 3 + k] + len * me->normals[i * 3 + k];
            }
    }
    glBindVertexArray(v->normal_vao);
    glBindBuffer(GL_ARRAY_BUFFER, v->normal_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(nv * 6 * sizeof *line), line, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), (void *)0);
    glBindVertexArray(0);
    free(line);
    v->normal_vertices = (GLsizei)(2 * nv);
}

/* All baked meshes into one vertex buffer (position, radiance) and one
 * index buffer. */
void il_view_upload_mesh(viewer *v, const il_bake_result *b, il_method method)
{
    size_t nv = 0, ni = 0;
    for (uint32_t m = 0; m < b->num_meshes; m++) {
        nv += b->meshes[m].num_vertices;
        ni += (size_t)b->meshes[m].num_triangles * 3;
    }
    float *vert = malloc(nv * 7 * sizeof *vert + 1);
    uint32_t *idx = malloc(ni * sizeof *idx + 1);
    if (!vert || !idx) {
        free(vert);
        free(idx);
        cli_error("view: out of memory for the mesh");
        return;
    }
    size_t bv = 0, bi = 0;
    bool specular = false;
    for (uint32_t m = 0; m < b->num_meshes; m++) {
        const il_bake_mesh *me = &b->meshes[m];
        for (uint32_t i = 0; i < me->num_vertices; i++) {
            for (int k = 0; k < 3; k++) {
                vert[(bv + i) * 7 + k] = me->positions[i * 3 + k];
                vert[(bv + i) * 7 + 3 + k] = me->radiance[i * 3 + k];
            }
            vert[(bv + i) * 7 + 6] = 1.0f;           /* a patch's vertex ... */
        }
        for (size_t i = 0; i < (size_t)me->num_triangles * 3; i++)
            idx[bi + i] = (uint32_t)bv + me->indices[i];
        /* ... unless on a triangle without one (mirror, glass): those have
         * vertices of their own (a surface is one material). */
        for (uint32_t t = 0; t < me->num_triangles; t++)
            if (me->patches && me->patches[t] == UINT32_MAX) {
                specular = true;
                for (int c = 0; c < 3; c++)
                    vert[(bv + me->indices[3 * (size_t)t + c]) * 7 + 6] = 0.5f;
            }
        bv += me->num_vertices;
        bi += (size_t)me->num_triangles * 3;
    }
    glBindVertexArray(v->mesh_vao);
    glBindBuffer(GL_ARRAY_BUFFER, v->mesh_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(nv * 7 * sizeof *vert), vert, GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, v->mesh_ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(ni * sizeof *idx), idx, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 7 * sizeof(float), (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 7 * sizeof(float),
                          (void *)(3 * sizeof(float)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, 7 * sizeof(float),
                          (void *)(6 * sizeof(float)));
    glBindVertexArray(0);
    upload_normals(v, b, nv);
    il_view_upload_patches(v, b);
    free(vert);
    free(idx);
    v->mesh_indices = (GLsizei)ni;
    v->has_mesh = true;
    v->mesh_method = method;
    v->mesh_specular = specular;
}

void il_view_draw_mesh(viewer *v, int fw, int fh)
{
    /* The framebuffer keeps the size at rest; a moving camera draws into
     * its corner, fw x fh. */
    int full = ss_factor(fw, fh);
    bool moving = v->moved || glfwGetTime() - v->last_move < REST_SECONDS;
    int ss = moving ? 1 : full;
    if (fw <= 0 || fh <= 0 || !ss_resize(v, fw * full, fh * full))
        return;
    bool background = il_view_update_background(v, fw, fh, moving);
    float mvp[16];
    il_view_camera_matrix(v, (float)fw / (float)fh, mvp);
    glBindFramebuffer(GL_FRAMEBUFFER, v->ss_fbo);
    glViewport(0, 0, fw * ss, fh * ss);
    glScissor(0, 0, fw * ss, fh * ss);
    glEnable(GL_SCISSOR_TEST);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_TEST);
    glUseProgram(v->mesh_prog);
    glUniformMatrix4fv(glGetUniformLocation(v->mesh_prog, "mvp"), 1, GL_TRUE, mvp);
    glUniform1f(glGetUniformLocation(v->mesh_prog, "scale"), exp2f(v->exposure));
    glUniform4f(glGetUniformLocation(v->mesh_prog, "line"), 0, 0, 0, 0);
    glBindVertexArray(v->mesh_vao);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    glDrawElements(GL_TRIANGLES, v->mesh_indices, GL_UNSIGNED_INT, 0);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glColorMaski(0, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);   /* lines: layer 1 only */
    if (v->wireframe) {
        glUniform4f(glGetUniformLocation(v->mesh_prog, "line"), 0.1f, 0.9f, 0.2f, 1.0f);
        glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        glDrawElements(GL_TRIANGLES, v->mesh_indices, GL_UNSIGNED_INT, 0);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    }
    if (v->patch_lines)
        il_view_draw_patches(v);
    if (v->normals && v->normal_vertices) {
        glUniform4f(glGetUniformLocation(v->mesh_prog, "line"), 1.0f, 0.2f, 1.0f, 1.0f);
        glBindVertexArray(v->normal_vao);
        glDrawArrays(GL_LINES, 0, v->normal_vertices);
    }
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fw, fh);
    glUseProgram(v->resolve_prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, v->ss_radiance);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, v->ss_lines);
    glUniform1i(glGetUniformLocation(v->resolve_prog, "radiance"), 0);
    glUniform1i(glGetUniformLocation(v->resolve_prog, "lines"), 1);
    glUniform1i(glGetUniformLocation(v->resolve_prog, "ss"), ss);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, background ? v->bg_tex : 0);
    glUniform1i(glGetUniformLocation(v->resolve_prog, "background"), 2);
    glUniform1i(glGetUniformLocation(v->resolve_prog, "has_background"), background);
    glUniform1f(glGetUniformLocation(v->resolve_prog, "scale"), exp2f(v->exposure));
    glUniform2f(glGetUniformLocation(v->resolve_prog, "size"), (float)fw, (float)fh);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, v->layer_ready ? v->layer_tex : 0);
    glUniform1i(glGetUniformLocation(v->resolve_prog, "layer"), 3);
    glUniform1i(glGetUniformLocation(v->resolve_prog, "has_layer"), v->layer_ready);
    glBindVertexArray(v->resolve_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glActiveTexture(GL_TEXTURE0);
}

void il_view_free_mesh(viewer *v)
{
    glDeleteProgram(v->resolve_prog);
    glDeleteVertexArrays(1, &v->resolve_vao);
    glDeleteFramebuffers(1, &v->ss_fbo);
    glDeleteTextures(1, &v->ss_radiance);
    glDeleteTextures(1, &v->ss_lines);
    glDeleteRenderbuffers(1, &v->ss_depth);
    il_view_free_patches(v);
    il_view_free_background(v);
    if (v->layer_tex)
        glDeleteTextures(1, &v->layer_tex);
}
