/* PLY: counts checked against the file's size before assimp reads it.
 *
 * assimp 5.2 sizes its arrays from a PLY header's element counts and from
 * each list's count before it reads the values, so a corrupt file of a few
 * hundred bytes that claims 2e9 vertices, or a face of 1.2e9 indices, makes
 * it allocate and touch 10-23 GB (minutes, or the out-of-memory killer).
 * This walks the header and the body (format: Turk, "The PLY polygon file
 * format", 1994) without storing anything, and refuses any count that the
 * rest of the file is too short to hold: in a binary file each value
 * takes at least its size, in an ASCII one each instance a line and each
 * list value a character and a separator.  A list's negative count is
 * refused (assimp reads it as 4e9 values), and so is a header of more
 * than 64 elements or 1024 properties, whose counts this could not check.
 * A header line that is not PLY is refused too (assimp 5.2 loops forever
 * on some, such as "element vertex 4.3" in a binary file).  A binary body
 * that ends early is left to assimp, which reports it. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "scene/loader.h"

enum { PLY_ASCII, PLY_LITTLE, PLY_BIG };

typedef struct ply_property {
    int size;       /* bytes of a scalar, or of each list value */
    int count_size; /* a list's count: 1, 2 or 4 bytes; 0 for a scalar */
    bool count_signed; /* its type is char, short or int (assimp 5.2 takes a
                          negative one as 4e9 values: it must be refused) */
} ply_property;

typedef struct ply_element {
    char name[32];
    uint64_t count;
    ply_property *props;
    int num_props;
} ply_element;

typedef struct ply_reader {
    const char *path;
    const unsigned char *p, *end;   /* the body still to walk */
    int format;
    il_error *err;
    bool stop;                      /* something unreadable: left to assimp */
} ply_reader;

/* The size of a PLY scalar type, 0 when unknown. */
static int type_size(const char *t)
{
    static const struct { const char *name; int size; } types[] = {
        {"char", 1}, {"int8", 1}, {"uchar", 1}, {"uint8", 1}, {"short", 2}, {"int16", 2},
        {"ushort", 2}, {"uint16", 2}, {"int", 4}, {"int32", 4}, {"uint", 4}, {"uint32", 4},
        {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (!strcmp(t, types[i].name))
            return types[i].size;
    return 0;
}

/* Whether PLY integer type t is signed. */
static bool type_signed(const char *t)
{
    return !strcmp(t, "char") || !strcmp(t, "int8") || !strcmp(t, "short") || !strcmp(t, "int16") ||
           !strcmp(t, "int") || !strcmp(t, "int32");
}

static il_status negative_count(ply_reader *r, const ply_element *e)
{
    return il_fail(r->err, IL_ERR_FORMAT, "%s: element '%s': a list with a negative count: the file "
                   "is corrupt", r->path, e->name);
}

/* n things (`what`) that the rest of the file cannot hold. */
static il_status too_short(ply_reader *r, const ply_element *e, const char *what, uint64_t n)
{
    return il_fail(r->err, IL_ERR_FORMAT, "%s: element '%s': %llu %s, more than the %llu "
                   "bytes left in the file can hold: the file is corrupt or truncated", r->path,
                   e->name, (unsigned long long)n, what, (unsigned long long)(r->end - r->p));
}

static bool is_blank(unsigned char c) { return c == ' ' || c == '\t' || c == '\r'; }

/* ASCII: the next token on the current line; false at the line's end. */
static bool next_token(ply_reader *r, const unsigned char **tok, size_t *len)
{
    while (r->p < r->end && is_blank(*r->p))
        r->p++;
    *tok = r->p;
    while (r->p < r->end && !is_blank(*r->p) && *r->p != '\n')
        r->p++;
    *len = (size_t)(r->p - *tok);
    return *len > 0;
}

/* ASCII: a list's count as assimp reads it, its leading digits (none: 0),
 * saturating. */
static uint64_t parse_count(const unsigned char *tok, size_t len)
{
    uint64_t n = 0;
    for (size_t i = 0; i < len && tok[i] >= '0' && tok[i] <= '9'; i++)
        n = n > (UINT64_MAX - 9) / 10 ? UINT64_MAX : 10 * n + (uint64_t)(tok[i] - '0');
    return n;
}

/* Binary: a count of `size` bytes in the file's byte order; *negative
 * when its type is signed and its top bit set. */
static uint64_t read_count(ply_reader *r, int size, bool is_signed, bool *negative)
{
    uint64_t v = 0;
    for (int i = 0; i < size; i++) {
        int k = r->format == PLY_LITTLE ? size - 1 - i : i;
        v = (v << 8) | r->p[k];
    }
    r->p += size;
    *negative = is_signed && (v >> (8 * size - 1)) != 0;
    return v;
}

/* One instance's properties.  False (not an error) when a binary file ends
 * early: assimp reports that itself.  An ASCII instance is one line, as
 * assimp reads it; a line shorter than its properties ends the instance. */
static bool walk_instance(ply_reader *r, const ply_element *e, il_status *s)
{
    const uint64_t value_bytes_ascii = 2;   /* a digit and a separator */
    if (r->format == PLY_ASCII)
        while (r->p < r->end && (is_blank(*r->p) || *r->p == '\n'))
            r->p++;
    for (int i = 0; i < e->num_props; i++) {
        const ply_property *q = &e->props[i];
        const unsigned char *tok;
        size_t len;
        uint64_t n = 0;
        if (r->format == PLY_ASCII) {
            if (!next_token(r, &tok, &len))
                break;
            if (!q->count_size)
                continue;
            if (tok[0] == '-') {
                *s = negative_count(r, e);
                return false;
            }
            n = parse_count(tok, len);
            if (n > (uint64_t)(r->end - r->p + 1) / value_bytes_ascii) {
                *s = too_short(r, e, "values in a list", n);
                return false;
            }
            for (uint64_t j = 0; j < n && next_token(r, &tok, &len); j++)
                ;
        } else {
            int head = q->count_size ? q->count_size : q->size;
            if (r->end - r->p < head)
                return false;
            if (!q->count_size) {
                r->p += q->size;
                continue;
            }
            bool negative;
            n = read_count(r, q->count_size, q->count_signed, &negative);
            if (negative) {
                *s = negative_count(r, e);
                return false;
            }
            if (n > (uint64_t)(r->end - r->p) / (uint64_t)q->size) {
                *s = too_short(r, e, "values in a list", n);
                return false;
            }
            r->p += n * (uint64_t)q->size;
        }
    }
    if (r->format == PLY_ASCII) {
        while (r->p < r->end && *r->p != '\n')
            r->p++;
        return r->p < r->end;
    }
    return true;
}

/* One element's instances, after checking that the file can hold their
 * count at the least size of each. */
static il_status walk_element(ply_reader *r, const ply_element *e)
{
    uint64_t least = r->format == PLY_ASCII ? 2 : 0;   /* ASCII: a character and a newline */
    for (int i = 0; i < e->num_props && r->format != PLY_ASCII; i++) {
        const ply_property *q = &e->props[i];
        least += (uint64_t)(q->count_size ? q->count_size : q->size);
    }
    uint64_t room = (uint64_t)(r->end - r->p) + (r->format == PLY_ASCII);
    if (least && e->count > room / least)
        return too_short(r, e, "instances", e->count);
    if (e->num_props == 0)
        return IL_OK;
    il_status s = IL_OK;
    for (uint64_t k = 0; k < e->count && !r->stop; k++)
        r->stop = !walk_instance(r, e, &s);
    return s;
}

enum { PLY_MAX_ELEMS = 64, PLY_MAX_PROPS = 1024 };

typedef struct ply_header {
    int format;
    ply_element elems[PLY_MAX_ELEMS];
    ply_property props[PLY_MAX_PROPS];
    int num_elems, num_props;
    char *body;
} ply_header;

/* One header line (NUL-terminated, after "ply") into h; NULL, or what is
 * wrong with it (more elements or properties than this check's tables
 * hold too: a count it could not check would reach assimp unchecked). */
static const char *header_line(const char *line, ply_header *h, bool *unsupported)
{
    char w[5][32] = {{0}};
    int fields = sscanf(line, "%31s %31s %31s %31s %31s", w[0], w[1], w[2], w[3], w[4]);
    if (fields <= 0 || !strcmp(w[0], "comment") || !strcmp(w[0], "obj_info"))
        return NULL;
    if (!strcmp(w[0], "format")) {
        h->format = !strcmp(w[1], "ascii")                  ? PLY_ASCII
                    : !strcmp(w[1], "binary_little_endian") ? PLY_LITTLE
                    : !strcmp(w[1], "binary_big_endian")    ? PLY_BIG
                                                            : -1;
        return h->format < 0 || fields != 3 ? "the format is not ascii, binary_little_endian or "
                                              "binary_big_endian with a version"
                                            : NULL;
    }
    if (!strcmp(w[0], "element")) {
        char *stop;
        if (fields != 3 || !(w[2][0] >= '0' && w[2][0] <= '9'))
            return "an element needs a name and a whole count";
        *unsupported = h->num_elems == PLY_MAX_ELEMS;
        if (*unsupported)
            return "more than 64 elements: illum reads PLY files with up to 64";
        ply_element *e = &h->elems[h->num_elems++];
        memcpy(e->name, w[1], sizeof e->name);
        e->count = strtoull(w[2], &stop, 10);
        e->props = h->props + h->num_props;
        e->num_props = 0;
        return *stop ? "an element needs a name and a whole count" : NULL;
    }
    if (!strcmp(w[0], "property")) {
        bool list = !strcmp(w[1], "list");
        ply_property q = {list ? type_size(w[3]) : type_size(w[1]), list ? type_size(w[2]) : 0,
                          list && type_signed(w[2])};
        if (h->num_elems == 0)
            return "a property before any element";
        if (q.size == 0 || fields != (list ? 5 : 3) || (list && (q.count_size == 0 || q.count_size == 8)))
            return "a property needs a known type (and a list an integer count type) and a name";
        *unsupported = h->num_props == PLY_MAX_PROPS;
        if (*unsupported)
            return "more than 1024 properties: illum reads PLY files with up to 1024";
        h->props[h->num_props++] = q;
        h->elems[h->num_elems - 1].num_props++;
        return NULL;
    }
    return "not a PLY header line (format, element, property, comment, obj_info, end_header)";
}

/* The header up to "end_header" into h. */
static il_status read_header(char *text, const char *path, ply_header *h, il_error *err)
{
    h->format = -1;
    h->num_elems = h->num_props = 0;
    char *line = text;
    for (int lineno = 1;; lineno++) {
        char *nl = strchr(line, '\n');
        if (!nl)
            return il_fail(err, IL_ERR_FORMAT, "%s: the PLY header has no end_header line: the "
                           "file is corrupt or truncated", path);
        *nl = '\0';
        if (nl > line && nl[-1] == '\r')
            nl[-1] = '\0';
        if (lineno == 1 && !(!strncmp(line, "ply", 3) && (line[3] == '\0' || line[3] == ' ')))
            return il_fail(err, IL_ERR_FORMAT, "%s: not a PLY file (its first line is not \"ply\")",
                           path);
        if (!strncmp(line, "end_header", 10) && (line[10] == '\0' || line[10] == ' ')) {
            h->body = nl + 1;
            if (h->format < 0)
                return il_fail(err, IL_ERR_FORMAT, "%s: the PLY header has no format line", path);
            return IL_OK;
        }
        bool unsupported = false;
        const char *why = lineno == 1 ? NULL : header_line(line, h, &unsupported);
        if (why)
            return il_fail(err, IL_ERR_FORMAT, "%s: line %d of the PLY header: %s%s", path, lineno, why,
                           unsupported ? "" : ": the file is corrupt");
        line = nl + 1;
    }
}

il_status il_ply_check(const char *path, il_error *err)
{
    char *text;
    size_t n;
    il_status s = il_load_read_file(path, &text, &n, err);
    if (s != IL_OK)
        return s;
    ply_header *h = malloc(sizeof *h);
    if (!h) {
        free(text);
        return il_fail(err, IL_ERR_MEMORY, "%s: out of memory", path);
    }
    s = read_header(text, path, h, err);
    if (s == IL_OK) {
        ply_reader r = {path, (const unsigned char *)h->body, (const unsigned char *)text + n, h->format,
                        err, false};
        for (int i = 0; i < h->num_elems && s == IL_OK && !r.stop; i++)
            s = walk_element(&r, &h->elems[i]);
    }
    free(h);
    free(text);
    return s;
}
