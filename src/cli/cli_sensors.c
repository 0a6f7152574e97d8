/* Where `illum illuminance` measures (cli.h): a grid on a plane, or the
 * points of a file. */
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli/cli.h"


float cli_axis_coord(il_vec3 v, int axis) { return axis == 0 ? v.x : (axis == 1 ? v.y : v.z); }

static void set_coord(il_vec3 *v, int axis, float value)
{
    if (axis == 0)
        v->x = value;
    else if (axis == 1)
        v->y = value;
    else
        v->z = value;
}

int cli_signed_axis(const char *s, float *sign, const char **rest)
{
    *sign = *s == '-' ? -1.0f : 1.0f;
    if (*s == '-' || *s == '+')
        s++;
    int axis = *s == 'x' ? 0 : (*s == 'y' ? 1 : (*s == 'z' ? 2 : -1));
    *rest = axis < 0 ? s : s + 1;
    return axis;
}

bool cli_parse_plane(const char *opt, const char *s, cli_plane *out)
{
    float sign;
    const char *rest;
    int axis = cli_signed_axis(s, &sign, &rest);
    if (axis < 0 || *rest != '=') {
        cli_error("%s: expected AXIS=VALUE such as y=0.85 (or -y=2.4 to face down), got '%s'", opt, s);
        return false;
    }
    double v = 0.0;
    if (!cli_parse_double(opt, rest + 1, -1e9, 1e9, &v))
        return false;
    out->axis = axis;
    out->sign = sign;
    out->value = (float)v;
    return true;
}

/* EN 12464-1:2011, 4.4: the largest grid cell p = 0.2 * 5^log10(d) metres,
 * d the longer side of the area, or the shorter one when the longer is at
 * least twice it; p at most 10 m. */
static double standard_cell(double a, double b)
{
    double lo = a < b ? a : b, hi = a < b ? b : a;
    double d = hi >= 2.0 * lo ? lo : hi;
    if (!(d > 0.0))
        d = hi;
    double p = 0.2 * pow(5.0, log10(d));
    return p > 10.0 ? 10.0 : p;
}

/* The plane's two other axes, in order (y plane: x, z). */
static void plane_axes(const cli_plane *plane, int *a0, int *a1)
{
    int b = (plane->axis + 1) % 3, c = (plane->axis + 2) % 3;
    *a0 = b < c ? b : c;
    *a1 = b < c ? c : b;
}

int cli_plane_grid(const cli_plane *plane, const double area[4], double spacing, cli_sensor_grid *g)
{
    int a0, a1;
    plane_axes(plane, &a0, &a1);
    double len0 = area[2] - area[0], len1 = area[3] - area[1];
    if (!(len0 > 0.0) || !(len1 > 0.0)) {
        cli_error("the measuring area is empty (%g by %g); give --area or a smaller --margin",
                  len0, len1);
        return IL_EXIT_BAD_INPUT;
    }
    if (!(len0 <= 1e15 && len1 <= 1e15)) {
        cli_error("the measuring area is %g by %g, out of range (at most 1e15 a side, as scene "
                  "coordinates)", len0, len1);
        return IL_EXIT_BAD_INPUT;
    }
    double p = spacing > 0.0 ? spacing : standard_cell(len0, len1);
    /* As many cells as the nearest whole number of lengths over p, with a
     * sensor at the centre of each (the standard's grid). */
    double n0 = fmax(1.0, floor(len0 / p + 0.5)), n1 = fmax(1.0, floor(len1 / p + 0.5));
    if (n0 * n1 > CLI_MAX_SENSORS) {
        cli_error("a grid of %.0f by %.0f points is more than %u; give a larger --spacing", n0, n1,
                  CLI_MAX_SENSORS);
        return IL_EXIT_BAD_INPUT;
    }
    g->axes[0] = a0;
    g->axes[1] = a1;
    g->cols = (uint32_t)n0;
    g->rows = (uint32_t)n1;
    g->cell[0] = len0 / n0;
    g->cell[1] = len1 / n1;
    g->count = (size_t)g->cols * g->rows;
    g->sensors = malloc(g->count * sizeof *g->sensors);
    if (!g->sensors) {
        cli_error("out of memory for %zu sensors", g->count);
        return IL_EXIT_RUNTIME;
    }
    il_vec3 normal = {0.0f, 0.0f, 0.0f};
    set_coord(&normal, plane->axis, plane->sign);
    for (uint32_t r = 0; r < g->rows; r++)
        for (uint32_t c = 0; c < g->cols; c++) {
            il_vec3 p3 = {0.0f, 0.0f, 0.0f};
            set_coord(&p3, plane->axis, plane->value);
            set_coord(&p3, a0, (float)(area[0] + (c + 0.5) * g->cell[0]));
            set_coord(&p3, a1, (float)(area[1] + (r + 0.5) * g->cell[1]));
            g->sensors[(size_t)r * g->cols + c] = (il_sensor){p3, normal};
        }
    return IL_EXIT_OK;
}

void cli_plane_area(const cli_plane *plane, il_vec3 lo, il_vec3 hi, double margin, double area[4])
{
    int a0, a1;
    plane_axes(plane, &a0, &a1);
    area[0] = cli_axis_coord(lo, a0) + margin;
    area[1] = cli_axis_coord(lo, a1) + margin;
    area[2] = cli_axis_coord(hi, a0) - margin;
    area[3] = cli_axis_coord(hi, a1) - margin;
}

bool cli_parse_area(const char *opt, const char *s, double area[4])
{
    if (!cli_parse_numbers(opt, s, 4, "four numbers A0,B0,A1,B1", area))
        return false;
    if (!(area[2] > area[0] && area[3] > area[1])) {
        cli_error("%s: the second corner must be beyond the first in both coordinates, got '%s'", opt, s);
        return false;
    }
    return true;
}

bool cli_sensor_place_option(const char *a, const char *v, cli_sensor_place *p, bool *ok)
{
    /* One place a run: a second --plane, --area or --points would replace
     * the first without a word. */
    if ((!strcmp(a, "--plane") && p->has_plane) || (!strcmp(a, "--area") && p->has_area) ||
        (!strcmp(a, "--points") && p->points)) {
        cli_error("%s: given twice (one a run; run the command again for another)", a);
        *ok = false;
        return true;
    }
    if (!strcmp(a, "--plane")) {
        *ok = cli_parse_plane(a, v, &p->plane);
        p->has_plane = true;
    } else if (!strcmp(a, "--area")) {
        *ok = cli_parse_area(a, v, p->area);
        p->has_area = true;
    } else if (!strcmp(a, "--margin")) {
        *ok = cli_parse_double(a, v, 0.0, 1e6, &p->margin);
    } else if (!strcmp(a, "--spacing")) {
        *ok = cli_parse_double(a, v, 1e-4, 1e6, &p->spacing);
    } else if (!strcmp(a, "--points")) {
        p->points = v;
        *ok = true;
    } else {
        return false;
    }
    return true;
}

int cli_plane_sensors(const il_scene *scene, cli_sensor_place *p, cli_sensor_grid *g)
{
    if (!p->has_area) {
        il_scene_info in;
        il_scene_get_info(scene, &in);
        cli_plane_area(&p->plane, in.bounds_min, in.bounds_max, p->margin, p->area);
    } else {
        p->area[0] += p->margin, p->area[1] += p->margin;
        p->area[2] -= p->margin, p->area[3] -= p->margin;
    }
    return cli_plane_grid(&p->plane, p->area, p->spacing, g);
}

void cli_print_sensors(const cli_sensor_grid *g, const cli_sensor_place *p)
{
    static const char names[] = "xyz";
    const cli_plane *plane = &p->plane;
    if (g->cols)
        printf("%zu sensors on %c = %g facing %c%c: %u x %u cells of %.3g x %.3g m\n", g->count,
               names[plane->axis], (double)plane->value, plane->sign > 0 ? '+' : '-', names[plane->axis],
               g->cols, g->rows, g->cell[0], g->cell[1]);
    else
        printf("%zu sensors from %s\n", g->count, p->points);
}

/* Up to 6 numbers of one line, separated by commas, spaces or tabs. */
static int parse_numbers(char *line, double v[6], bool *junk)
{
    int n = 0;
    char *p = line;
    *junk = false;
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == ',' || *p == '\r' || *p == '\n')
            p++;
        if (!*p)
            return n;
        char *end;
        errno = 0;
        double x = strtod(p, &end);
        if (end == p || errno == ERANGE || !(fabs(x) <= FLT_MAX) || n == 6) {
            *junk = true;
            return n;
        }
        v[n++] = x;
        p = end;
    }
}

int cli_read_sensors(const char *path, cli_sensor_grid *g)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        cli_error("%s: cannot open the sensor file: %s", path, strerror(errno));
        return IL_EXIT_BAD_INPUT;
    }
    size_t cap = 0;
    char line[4096];
    int rc = IL_EXIT_OK;
    for (unsigned long no = 1; fgets(line, sizeof line, f); no++) {
        if (!strchr(line, '\n') && !feof(f)) {
            cli_error("%s:%lu: line longer than %zu characters", path, no, sizeof line - 1);
            rc = IL_EXIT_BAD_INPUT;
            break;
        }
        char *s = line;
        while (isspace((unsigned char)*s))
            s++;
        char *hash = strchr(s, '#');
        if (hash)
            *hash = '\0';   /* a comment, whole-line or after the numbers */
        if (!*s)
            continue;
        /* A CSV header such as x,y,z,nx,ny,nz (a word, but not nan or inf,
         * which are bad numbers). */
        if (no == 1 && isalpha((unsigned char)*s) && strncasecmp(s, "nan", 3) && strncasecmp(s, "inf", 3))
            continue;
        double v[6];
        bool junk;
        int n = parse_numbers(s, v, &junk);
        if (junk || (n != 3 && n != 6)) {
            cli_error("%s:%lu: expected 'x y z' or 'x y z nx ny nz' (finite numbers within "
                      "+-3.4e38, separated by spaces or commas)", path, no);
            rc = IL_EXIT_BAD_INPUT;
            break;
        }
        il_sensor sn = {{(float)v[0], (float)v[1], (float)v[2]}, {0.0f, 1.0f, 0.0f}};
        if (n == 6) {
            double len = sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]);
            if (!(len > 0.0) || !isfinite(len)) {
                cli_error("%s:%lu: the normal is zero", path, no);
                rc = IL_EXIT_BAD_INPUT;
                break;
            }
            sn.normal = (il_vec3){(float)(v[3] / len), (float)(v[4] / len), (float)(v[5] / len)};
        }
        if (g->count == CLI_MAX_SENSORS) {
            cli_error("%s: more than %u sensors", path, CLI_MAX_SENSORS);
            rc = IL_EXIT_BAD_INPUT;
            break;
        }
        if (g->count == cap) {
            cap = cap ? 2 * cap : 256;
            il_sensor *grown = realloc(g->sensors, cap * sizeof *grown);
            if (!grown) {
                cli_error("out of memory reading %s", path);
                rc = IL_EXIT_RUNTIME;
                break;
            }
            g->sensors = grown;
        }
        g->sensors[g->count++] = sn;
    }
    if (rc == IL_EXIT_OK && ferror(f)) {
        cli_error("%s: read error", path);
        rc = IL_EXIT_BAD_INPUT;
    }
    fclose(f);
    if (rc == IL_EXIT_OK && g->count == 0) {
        cli_error("%s: no sensor in the file (expected lines 'x y z [nx ny nz]')", path);
        rc = IL_EXIT_BAD_INPUT;
    }
    return rc;
}
