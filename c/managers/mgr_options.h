/* chasm-manager's command line, as parsed (mgr_args.c). The manager copies
 * it when it is created and never changes it: what changes while it runs
 * (the plan, whether it waits for a CMD_START) is manager state (manager.h). */
#ifndef MGR_OPTIONS_H
#define MGR_OPTIONS_H

#include <stddef.h>
#include <stdint.h>

#include "managers/mgr_limits.h"

typedef struct {
    const char *plan_path, *bind_path, *vehicle, *name, *url;
    int sim_clock;              /* 1: SIM.CLOCK drives the cycle; 0: system clock */
    double rate_hz;
    double status_rate_hz;      /* --status-rate: 0, a status every cycle */
    int exit_on_end;            /* leave when the plan is done/aborted/failed */
    int wait_start;             /* start only on a CMD_START */
    const char *plugin_dir;     /* where uploads are written; also searched first */
    const char *allowlist;      /* file of "sha256hex [name]" lines; NULL: refuse uploads */
    const char *key_file;       /* --key-file: team keys; NULL: commands are not authenticated */
    const char *plugin_path[MGR_MAX_PLUGIN_PATH];
    size_t n_plugin_path;
    const char *param_names[MGR_MAX_PARAMS], *param_values[MGR_MAX_PARAMS];
    size_t n_params;
    int64_t future_tol_us;      /* --future-tolerance S: data stamped further ahead is dropped */
    int64_t max_clock_jump_us;  /* --max-clock-jump S */
} manager_options;

/* Every option checked (numbers in range, names that make valid channels,
 * -D as name=value, which splits its argv string in place); --help on
 * stdout. 0, 1 after --help (exit 0) or -1 on a usage error (exit 2). */
int manager_parse_args(manager_options *o, int argc, char **argv);

#endif
