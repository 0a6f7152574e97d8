/* What the method-specific option sets (cli_radiosity.c, cli_hr.c, cli_photon.c,
 * cli_ibl.c) share:
 * method names, matching an option of a set and fetching its value, the
 * --help check, and the usage error for an option of another method. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"

static const struct {
    const char *name;
    il_method method;
} methods[] = {
    {"pt", IL_METHOD_PT},
    {"radiosity", IL_METHOD_RADIOSITY},
    {"hr", IL_METHOD_HR},
    {"photon", IL_METHOD_PHOTON},
    {"sppm", IL_METHOD_SPPM},
    {"ibl", IL_METHOD_IBL},
    {"linespace", IL_METHOD_LINESPACE},
    {"rsm", IL_METHOD_RSM},
};

bool cli_method_from_name(const char *name, il_method *out)
{
    for (size_t k = 0; k < sizeof methods / sizeof methods[0]; k++)
        if (!strcmp(name, methods[k].name)) {
            *out = methods[k].method;
            return true;
        }
    return false;
}

const char *cli_method_name(il_method method)
{
    for (size_t k = 0; k < sizeof methods / sizeof methods[0]; k++)
        if (methods[k].method == method)
            return methods[k].name;
    return "unknown";
}

const char *cli_method_option(int argc, char **argv, int *i, const char *const *names, size_t n,
                              cli_method_note *note, const char **value)
{
    const char *name = NULL;
    for (size_t k = 0; k < n && !name; k++)
        if (!strcmp(argv[*i], names[k]))
            name = names[k];
    if (!name)
        return NULL;
    *value = cli_value(argc, argv, i);
    if (*value) {
        note->given = true;
        if (!note->first)
            note->first = name;
    }
    return name;
}

bool cli_help_wants_method(int argc, char **argv, const char *method)
{
    for (int k = 1; k + 1 < argc; k++)
        if (!strcmp(argv[k], "--method") && !strcmp(argv[k + 1], method))
            return true;
    return false;
}

int cli_method_mismatch(const char *command, const cli_method_note *note, const char *label,
                        const char *method)
{
    cli_error("%s is a %s option; it needs --method %s (see 'illum %s --method %s --help')",
              note->first, label, method, command, method);
    return IL_EXIT_USAGE;
}

/* The options of every method that traces light paths. */
static const char *const light_path_names[] = {"--portal-light"};

static bool light_path_option(int argc, char **argv, int *i, cli_method_options *m, int *rc)
{
    const char *v = NULL;
    const char *name = cli_method_option(argc, argv, i, light_path_names,
                                         sizeof light_path_names / sizeof light_path_names[0],
                                         &m->light_paths, &v);
    if (!name)
        return false;
    bool on = true;
    *rc = !v ? IL_EXIT_USAGE : cli_parse_on_off(name, v, &on) ? IL_EXIT_OK : IL_EXIT_BAD_INPUT;
    m->photon.desc.no_portal_light = !on;
    m->linespace.desc.no_portal_light = !on;
    return true;
}

int cli_method_light_paths_check(const char *command, const cli_method_options *m, il_method method)
{
    if (!m->light_paths.given || method == IL_METHOD_PHOTON || method == IL_METHOD_SPPM ||
        method == IL_METHOD_LINESPACE)
        return IL_EXIT_OK;
    cli_error("%s is an option of the methods that trace light paths; it needs --method photon, "
              "sppm or linespace (see 'illum %s --method photon --help')",
              m->light_paths.first, command);
    return IL_EXIT_USAGE;
}

bool cli_method_options_parse(int argc, char **argv, int *i, cli_method_options *m, int *rc)
{
    return light_path_option(argc, argv, i, m, rc) || cli_radiosity_option(argc, argv, i, &m->rad, rc) ||
           cli_hr_option(argc, argv, i, &m->hr, rc) ||
           cli_photon_option(argc, argv, i, &m->photon, rc) ||
           cli_ibl_option(argc, argv, i, &m->ibl, rc) ||
           cli_rsm_option(argc, argv, i, &m->rsm, rc) ||
           cli_linespace_option(argc, argv, i, &m->linespace, rc);
}

void cli_method_options_install(cli_method_options *m, il_render_desc *desc)
{
    desc->radiosity = &m->rad.desc;
    desc->hr = &m->hr.desc;
    desc->photon = &m->photon.desc;
    desc->ibl = &m->ibl.desc;
    desc->rsm = &m->rsm.desc;
    desc->linespace = &m->linespace.desc;
}
