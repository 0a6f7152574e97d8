/* The viewer's image display: the worker's latest HDR image tone-mapped on
 * the CPU with il_tonemap (the same curves and rounding as `illum render`
 * PNGs) and drawn as a texture by one triangle covering the window. */
#include <math.h>
#include <stdlib.h>

#include "cli/cli.h"
#include "viewer/viewer_internal.h"

GLuint il_view_compile(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        cli_error("view: shader: %s", log);
        glDeleteShader(s);
        return 0;
    }
    return s;
}

/* One triangle covering the screen, its corners from gl_VertexID. */
bool il_view_make_image_program(viewer *v)
{
    static const char *vs =
        "#version 330 core\n"
        "out vec2 uv;\n"
        "void main() {\n"
        "    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
        "    uv = vec2(p.x, 1.0 - p.y);\n"   /* image rows run top to bottom */
        "    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
        "}\n";
    static const char *fs =
        "#version 330 core\n"
        "in vec2 uv;\n"
        "out vec4 color;\n"
        "uniform sampler2D image;\n"
        "void main() { color = vec4(texture(image, uv).rgb, 1.0); }\n";
    GLuint a = il_view_compile(GL_VERTEX_SHADER, vs), b = il_view_compile(GL_FRAGMENT_SHADER, fs);
    if (!a || !b)
        return false;
    v->prog = glCreateProgram();
    glAttachShader(v->prog, a);
    glAttachShader(v->prog, b);
    glLinkProgram(v->prog);
    glDeleteShader(a);
    glDeleteShader(b);
    GLint ok = 0;
    glGetProgramiv(v->prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        cli_error("view: the shader program does not link");
        return false;
    }
    glGenVertexArrays(1, &v->vao);
    glGenTextures(1, &v->tex);
    glBindTexture(GL_TEXTURE_2D, v->tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return true;
}

/* Tone-maps v->shown with il_tonemap and uploads it as 8-bit texels,
 * rounded as the PNG writer rounds. */
void il_view_upload_image(viewer *v)
{
    if (!v->shown.rgb)
        return;
    il_tonemap_desc tm = {.op = v->op, .exposure = v->exposure};
    il_image disp = {0};
    il_error err = {0};
    if (il_tonemap(&v->shown, &tm, &disp, &err) != IL_OK) {
        cli_error("%s", err.message);
        return;
    }
    size_t n = (size_t)disp.width * disp.height * 3;
    unsigned char *px = malloc(n);
    if (px) {
        for (size_t i = 0; i < n; i++) {
            float c = fminf(1.0f, fmaxf(0.0f, disp.rgb[i]));
            px[i] = (unsigned char)(c * 255.0f + 0.5f);
        }
        int fw, fh;
        glfwGetFramebufferSize(v->win, &fw, &fh);
        GLint filter = (int)disp.width == fw && (int)disp.height == fh ? GL_NEAREST : GL_LINEAR;
        glBindTexture(GL_TEXTURE_2D, v->tex);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, (GLsizei)disp.width, (GLsizei)disp.height, 0,
                     GL_RGB, GL_UNSIGNED_BYTE, px);
        free(px);
    }
    il_image_free(&disp);
}

/* The worker's image, tone-mapped by il_view_upload_image, stretched over
 * the window. */
void il_view_draw_image(viewer *v)
{
    glUseProgram(v->prog);
    glBindVertexArray(v->vao);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, v->tex);
    glUniform1i(glGetUniformLocation(v->prog, "image"), 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}
