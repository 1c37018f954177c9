/* chasm-manager's command line (mgr_options.h): every option checked
 * (numbers in range, names that make valid channels, -D as name=value),
 * --help on stdout. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chasm/chasm.h"
#include "common/time_policy.h"
#include "managers/mgr_options.h"

static void usage(FILE *out)
{
    fprintf(out, "usage: chasm-manager --plan FILE --bind FILE --vehicle ID --name NAME [--rate HZ] [--status-rate HZ]\n"
                 "       [--clock sim|system] [--lcm-url URL] [--exit-on-end] [--wait-start]\n"
                 "       [--plugin-path DIR]... [--plugin-dir DIR --allowlist FILE] [-D name=value]...\n"
                 "       [--future-tolerance S] [--max-clock-jump S] [--key-file FILE]\n"
                 "  --lcm-url URL          LCM URL (default: $LCM_DEFAULT_URL, else liblcm's default);\n"
                 "                         --url is the old spelling of it\n"
                 "  --rate HZ              cycles per second of mission time, 0 < HZ <= %d (default 10)\n"
                 "  --status-rate HZ       status messages per second of mission time at most, besides one\n"
                 "                         at once on every change of state or count (default 0: every cycle)\n"
                 "  --plugin-path DIR      where plugins are found (default: the build's plugins,\n"
                 "                         <this program's folder>/../plugins)\n"
                 "  -D name=value          override a plan parameter: one value of its type and unit\n"
                 "                         (at most %d overrides)\n"
                 "  --future-tolerance S   drop input messages stamped more than S ahead of the clock (default 1)\n"
                 "  --max-clock-jump S     a clock jump over S needs a second message to confirm it (default 60)\n"
                 "  --key-file FILE        team key file (auv-keygen, mode 0600): mission commands and uploads\n"
                 "                         must be signed with one of its keys (docs/security.md); without it\n"
                 "                         commands are not authenticated\n",
            MGR_MAX_RATE_HZ, MGR_MAX_PARAMS);
}

/* A number option: finite, within [lo, hi]; -1 with a message otherwise. */
static int number_arg(const char *opt, const char *v, double lo, double hi, double *out)
{
    char *end;
    errno = 0;
    double x = strtod(v, &end);
    if (end == v || *end || errno || !(x >= lo && x <= hi)) {
        fprintf(stderr, "chasm-manager: %s wants a number from %g to %g, not '%s'\n", opt, lo, hi, v);
        return -1;
    }
    *out = x;
    return 0;
}

static int id_ok(const char *s)
{
    if (!*s)
        return 0;
    for (; *s; s++)
        if (!((*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') || *s == '_'))
            return 0;
    return 1;
}

/* --rate, --status-rate, --future-tolerance, --max-clock-jump: 1 taken, 0 none of them,
 * -1 out of range (said). */
static int number_option(manager_options *o, const char *a, const char *v)
{
    double x;
    if (!strcmp(a, "--rate"))
        return number_arg(a, v, 1e-3, MGR_MAX_RATE_HZ, &o->rate_hz) ? -1 : 1;
    if (!strcmp(a, "--status-rate"))
        return number_arg(a, v, 0, MGR_MAX_RATE_HZ, &o->status_rate_hz) ? -1 : 1;
    if (!strcmp(a, "--future-tolerance")) {
        if (number_arg(a, v, 0, MGR_MAX_FUTURE_TOLERANCE_S, &x))
            return -1;
        o->future_tol_us = (int64_t)(x * 1e6);
        return 1;
    }
    if (!strcmp(a, "--max-clock-jump")) {
        if (number_arg(a, v, 1e-3, MGR_MAX_CLOCK_JUMP_S, &x))
            return -1;
        o->max_clock_jump_us = (int64_t)(x * 1e6);
        return 1;
    }
    return 0;
}

static int plugin_path_option(manager_options *o, const char *v)
{
    if (o->n_plugin_path + 1 >= MGR_MAX_PLUGIN_PATH) { /* one place is kept for --plugin-dir */
        fprintf(stderr, "chasm-manager: at most %d --plugin-path folders\n", MGR_MAX_PLUGIN_PATH - 1);
        return -1;
    }
    o->plugin_path[o->n_plugin_path++] = v;
    return 1;
}

/* -D name=value: split in place (argv is ours). libchasm checks the name
 * against the plan and the value as one value of its type. */
static int define_option(manager_options *o, char *v)
{
    char *eq = strchr(v, '=');
    if (!eq || eq == v) {
        fprintf(stderr, "chasm-manager: -D wants name=value, not '%s'\n", v);
        return -1;
    }
    if (o->n_params >= MGR_MAX_PARAMS) {
        fprintf(stderr, "chasm-manager: at most %d -D overrides\n", MGR_MAX_PARAMS);
        return -1;
    }
    *eq = '\0';
    o->param_names[o->n_params] = v;
    o->param_values[o->n_params++] = eq + 1;
    return 1;
}

/* An option with a value v: 1 taken, 0 not such an option (or --clock with
 * another value), -1 refused (said). */
static int value_option(manager_options *o, const char *a, char *v)
{
    if (!strcmp(a, "--plan")) o->plan_path = v;
    else if (!strcmp(a, "--bind")) o->bind_path = v;
    else if (!strcmp(a, "--vehicle")) o->vehicle = v;
    else if (!strcmp(a, "--name")) o->name = v;
    else if (!strcmp(a, "--lcm-url") || !strcmp(a, "--url")) o->url = v;
    else if (!strcmp(a, "--clock") && (!strcmp(v, "sim") || !strcmp(v, "system"))) o->sim_clock = !strcmp(v, "sim");
    else if (!strcmp(a, "--plugin-dir")) o->plugin_dir = v;
    else if (!strcmp(a, "--allowlist")) o->allowlist = v;
    else if (!strcmp(a, "--key-file")) o->key_file = v;
    else if (!strcmp(a, "--plugin-path")) return plugin_path_option(o, v);
    else if (!strcmp(a, "-D")) return define_option(o, v);
    else return number_option(o, a, v);
    return 1;
}

/* What the options do not say explicitly, and whether what they say fits. */
static int complete(manager_options *o)
{
    if (!o->plan_path || !o->bind_path || !o->vehicle || !o->name) {
        usage(stderr);
        return -1;
    }
    /* Every channel the manager names must fit LCM's limit, the longest
     * being <VEHICLE>.PLUGIN_UPLOAD and <VEHICLE>.CHASM.<NAME>. */
    if (!id_ok(o->vehicle) || !id_ok(o->name) || strlen(o->vehicle) > MGR_MAX_VEHICLE ||
        strlen(o->vehicle) + strlen(".CHASM.") + strlen(o->name) > MGR_MAX_CHANNEL) {
        fprintf(stderr, "chasm-manager: --vehicle (1 to %d) and --name are letters, digits and '_', and "
                        "<VEHICLE>.CHASM.<NAME> at most %d characters\n", MGR_MAX_VEHICLE, MGR_MAX_CHANNEL);
        return -1;
    }
    /* No --plugin-path: the plugins built beside this program, as `chasm` does. */
    static char self_plugins[4096];
    if (!o->n_plugin_path && chasm_default_plugin_dir(self_plugins, sizeof self_plugins))
        o->plugin_path[o->n_plugin_path++] = self_plugins;
    if (o->plugin_dir) {
        /* Uploaded plugins take precedence over installed ones. */
        memmove(o->plugin_path + 1, o->plugin_path, o->n_plugin_path * sizeof o->plugin_path[0]);
        o->plugin_path[0] = o->plugin_dir;
        o->n_plugin_path++;
    }
    return 0;
}

int manager_parse_args(manager_options *o, int argc, char **argv)
{
    memset(o, 0, sizeof *o);
    o->rate_hz = 10.0;
    o->sim_clock = 1;
    o->url = NULL; /* liblcm then honours LCM_DEFAULT_URL */
    o->future_tol_us = TP_FUTURE_TOLERANCE_US;
    o->max_clock_jump_us = TP_MAX_CLOCK_JUMP_US;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 1;
        }
        int taken = i + 1 < argc ? value_option(o, a, argv[i + 1]) : 0;
        if (taken < 0)
            return -1;
        if (taken)
            i++;
        else if (!strcmp(a, "--exit-on-end"))
            o->exit_on_end = 1;
        else if (!strcmp(a, "--wait-start"))
            o->wait_start = 1;
        else {
            fprintf(stderr, "chasm-manager: bad or incomplete option '%s' (see --help)\n", a);
            return -1;
        }
    }
    return complete(o);
}
