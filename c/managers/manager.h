/* One manager process: one CHASM, run cyclically on the mission clock, with
 * its blackboard bound to LCM channels. Navigator, pilot and any other
 * controller are this same program with different plans and bindings. */
#ifndef MANAGER_H
#define MANAGER_H

#include <lcm/lcm.h>

#include "chasm/chasm.h"
#include "managers/mgr_bindings.h"
#include "managers/mgr_lockstep.h"
#include "managers/mgr_status.h"

typedef struct {
    const char *plan_path, *bind_path, *vehicle, *name, *url;
    int sim_clock;              /* 1: SIM.CLOCK drives the cycle; 0: system clock */
    double rate_hz;
    int exit_on_end;            /* leave when the plan is done/aborted/failed */
    int wait_start;             /* start only on a CMD_START */
    const char *plugin_dir;     /* where uploads are written; also searched first */
    const char *allowlist;      /* file of "sha256hex [name]" lines; NULL: refuse uploads */
    const char *plugin_path[16];
    size_t n_plugin_path;
    const char *param_names[64], *param_values[64];
    size_t n_params;
} manager_options;

typedef struct {
    manager_options opt;
    chasm_options chasm_opt;
    lcm_t *lcm;
    chasm_machine *m;
    mgr_bindings b;
    mgr_status_ctx status;
    int64_t now_us;             /* mission time of the latest clock reading */
    int have_time;
    int started;
    volatile int stop;
    rx_sub_t *cmd_sub, *upload_sub, *clock_sub;
    mgr_lockstep lockstep;      /* lockstep participation (SIM.CLOCK mode) */
} manager_t;

int manager_parse_args(manager_options *o, int argc, char **argv);
/* Load plan + bindings into a fresh machine; on errors prints them and returns NULL. */
chasm_machine *manager_load(manager_t *mg, const char *name, const char *text, mgr_bindings *out_b);
/* Mission command and plugin-upload channels. */
int mgr_commands_subscribe(manager_t *mg);
void mgr_commands_unsubscribe(manager_t *mg);
uint64_t mgr_commands_decode_errors(const manager_t *mg);

#endif
