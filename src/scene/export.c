/* il_bake_write: baked meshes to a file, chosen by extension (.ply, .glb,
 * .gltf), and the PLY writer.
 *
 * PLY (Turk 1994; the format as documented by Paul Bourke, "PLY - Polygon
 * File Format", paulbourke.net/dataformats/ply/): binary little-endian, one
 * vertex element with float x y z nx ny nz, uchar red green blue (display
 * colour: sRGB of radiance * 2^exposure, clamped) and float radiance_r
 * radiance_g radiance_b (the linear HDR radiance, W/(sr m^2)), one face
 * element of uchar count + uint indices.  All meshes go into one PLY, their
 * indices offset by the vertices before them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/srgb.h"
#include "scene/export.h"

void il_bake_display_rgb(const float *radiance, float scale, float out[3])
{
    bool finite = radiance && isfinite(radiance[0]) && isfinite(radiance[1]) && isfinite(radiance[2]);
    for (int k = 0; k < 3; k++)
        out[k] = finite ? radiance[k] * scale : 0.0f;
}

static void put_u32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v & 0xffu);
    p[1] = (unsigned char)((v >> 8) & 0xffu);
    p[2] = (unsigned char)((v >> 16) & 0xffu);
    p[3] = (unsigned char)((v >> 24) & 0xffu);
}

static void put_f32(unsigned char *p, float f)
{
    uint32_t v;
    memcpy(&v, &f, sizeof v);
    put_u32(p, v);
}

#define PLY_VERTEX_BYTES (6 * 4 + 3 + 3 * 4)
#define PLY_FACE_BYTES (1 + 3 * 4)
#define PLY_CHUNK 4096 /* vertices or faces per fwrite */

static const float ply_zero[3] = {0.0f, 0.0f, 0.0f};

static il_status write_ply_body(FILE *f, const il_bake_result *bake, float scale, const char *path,
                                uint64_t num_vertices, uint64_t num_faces, float exposure,
                                il_error *err)
{
    if (fprintf(f,
                "ply\n"
                "format binary_little_endian 1.0\n"
                "comment illum bake: radiance_r/g/b = outgoing radiance, W/(sr m^2), linear Rec.709\n"
                "comment red/green/blue = sRGB(radiance * 2^%g), clamped\n"
                "element vertex %llu\n"
                "property float x\nproperty float y\nproperty float z\n"
                "property float nx\nproperty float ny\nproperty float nz\n"
                "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                "property float radiance_r\nproperty float radiance_g\nproperty float radiance_b\n"
                "element face %llu\n"
                "property list uchar uint vertex_indices\n"
                "end_header\n",
                (double)exposure, (unsigned long long)num_vertices,
                (unsigned long long)num_faces) < 0)
        return il_fail(err, IL_ERR_IO, "%s: cannot write", path);

    unsigned char buf[PLY_CHUNK * PLY_VERTEX_BYTES];
    for (uint32_t m = 0; m < bake->num_meshes; m++) {
        const il_bake_mesh *bm = &bake->meshes[m];
        size_t n = 0;
        for (uint32_t v = 0; v < bm->num_vertices; v++) {
            unsigned char *p = buf + n * PLY_VERTEX_BYTES;
            const float *pos = bm->positions + 3 * (size_t)v;
            const float *nrm = bm->normals ? bm->normals + 3 * (size_t)v : ply_zero;
            const float *rad = bm->radiance ? bm->radiance + 3 * (size_t)v : ply_zero;
            float disp[3];
            il_bake_display_rgb(rad, scale, disp);
            for (int k = 0; k < 3; k++) {
                put_f32(p + 4 * k, pos[k]);
                put_f32(p + 12 + 4 * k, nrm[k]);
                p[24 + k] = il_linear_to_srgb8(disp[k]);
                put_f32(p + 27 + 4 * k, rad[k]);
            }
            if (++n == PLY_CHUNK || v + 1 == bm->num_vertices) {
                if (fwrite(buf, PLY_VERTEX_BYTES, n, f) != n)
                    return il_fail(err, IL_ERR_IO, "%s: cannot write", path);
                n = 0;
            }
        }
    }
    uint32_t offset = 0;
    for (uint32_t m = 0; m < bake->num_meshes; m++) {
        const il_bake_mesh *bm = &bake->meshes[m];
        size_t n = 0;
        for (uint32_t t = 0; t < bm->num_triangles; t++) {
            unsigned char *p = buf + n * PLY_FACE_BYTES;
            p[0] = 3;
            for (int k = 0; k < 3; k++)
                put_u32(p + 1 + 4 * k, bm->indices[3 * (size_t)t + k] + offset);
            if (++n == PLY_CHUNK || t + 1 == bm->num_triangles) {
                if (fwrite(buf, PLY_FACE_BYTES, n, f) != n)
                    return il_fail(err, IL_ERR_IO, "%s: cannot write", path);
                n = 0;
            }
        }
        offset += bm->num_vertices;
    }
    return IL_OK;
}

il_status il_bake_write_ply(const il_bake_result *bake, const char *path, float exposure,
                            il_error *err)
{
    uint64_t nv = 0, nf = 0;
    for (uint32_t m = 0; m < bake->num_meshes; m++) {
        nv += bake->meshes[m].num_vertices;
        nf += bake->meshes[m].num_triangles;
    }
    if (nv > UINT32_MAX)
        return il_fail(err, IL_ERR_INVALID, "%s: %llu vertices do not fit a PLY's uint indices", path,
                       (unsigned long long)nv);
    il_atomic_file af;
    il_status st = il_atomic_open(&af, path, err);
    if (st != IL_OK)
        return st;
    st = write_ply_body(af.f, bake, exp2f(exposure), path, nv, nf, exposure, err);
    return il_atomic_close(&af, st, err);
}

/* Every mesh has its arrays and in-range indices: a bad bake gives an error,
 * never a file that points outside its vertices. */
static il_status check_bake(const il_bake_result *bake, const char *path, il_error *err)
{
    if (!bake || (bake->num_meshes && !bake->meshes))
        return il_fail(err, IL_ERR_INVALID, "%s: no bake result to write", path);
    for (uint32_t m = 0; m < bake->num_meshes; m++) {
        const il_bake_mesh *bm = &bake->meshes[m];
        if ((bm->num_vertices && !bm->positions) || (bm->num_triangles && !bm->indices))
            return il_fail(err, IL_ERR_INVALID, "%s: baked mesh %u has no positions or indices", path,
                           m);
        for (uint64_t i = 0; i < 3 * (uint64_t)bm->num_triangles; i++)
            if (bm->indices[i] >= bm->num_vertices)
                return il_fail(err, IL_ERR_INVALID,
                               "%s: baked mesh %u: index %u out of range (%u vertices)", path, m,
                               bm->indices[i], bm->num_vertices);
    }
    return IL_OK;
}

static bool has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), k = strlen(ext);
    return n > k && strcasecmp(path + n - k, ext) == 0;
}

il_status il_bake_write(const il_bake_result *bake, const char *path, const il_bake_write_desc *desc,
                        il_error *err)
{
    il_error local;
    if (!err)
        err = &local;
    if (!path || !path[0])
        return il_fail(err, IL_ERR_INVALID, "no output file given for the bake");
    float exposure = desc ? desc->exposure : 0.0f;
    if (!isfinite(exposure) || fabsf(exposure) > 100.0f)
        return il_fail(err, IL_ERR_INVALID, "%s: exposure %g out of range", path, (double)exposure);
    bool ply = has_extension(path, ".ply"), glb = has_extension(path, ".glb"),
         gltf = has_extension(path, ".gltf");
    if (!ply && !glb && !gltf)
        return il_fail(err, IL_ERR_INVALID, "%s: unknown bake format (use .ply, .glb or .gltf)", path);
    il_status st = check_bake(bake, path, err);
    if (st != IL_OK)
        return st;
    if (ply)
        return il_bake_write_ply(bake, path, exposure, err);
    return il_bake_write_gltf(bake, path, exposure, glb, err);
}
