/* One manager process: one CHASM, run cyclically on the mission clock, with
 * its blackboard bound to LCM channels. Navigator, pilot and any other
 * controller are this same program with different plans and bindings. */
#ifndef MANAGER_H
#define MANAGER_H

#include <lcm/lcm.h>

#include "chasm/chasm.h"
#include "common/time_policy.h"
#include "managers/mgr_bindings.h"
#include "managers/mgr_errors.h"
#include "managers/mgr_lockstep.h"
#include "managers/mgr_status.h"

/* Sizes the manager accepts; each has a refusal with a reason (docs/managers.md
 * and docs/channels.md say them). */
#define MGR_MAX_PLAN_BYTES (256 * 1024)     /* LOAD_PLAN plan_text, documented maximum */
#define MGR_MIN_PLAN_BYTES (32 * 1024)      /* the least a too-small receive buffer falls back to */
#define MGR_MAX_PLAN_NAME 255               /* LOAD_PLAN plan_name, characters */
#define MGR_MAX_REASON 1024                 /* a command's reason, characters */
#define MGR_MAX_VEHICLE 48                  /* --vehicle: <VEHICLE>.PLUGIN_UPLOAD fits LCM's 63 */
#define MGR_ACK_MAX_ERRORS 5                /* errors quoted in a rejected LOAD_PLAN's ack */
#define MGR_ACK_MAX_CHARS 2000              /* an ack's message, characters */
#define MGR_MAX_PARAMS 64                   /* -D overrides */
#define MGR_MAX_RATE_HZ 1000                /* --rate */
#define MGR_MAX_PLUGIN_PATH 16              /* --plugin-path folders (with --plugin-dir) */

typedef struct {
    const char *plan_path, *bind_path, *vehicle, *name, *url;
    int sim_clock;              /* 1: SIM.CLOCK drives the cycle; 0: system clock */
    double rate_hz;
    int exit_on_end;            /* leave when the plan is done/aborted/failed */
    int wait_start;             /* start only on a CMD_START */
    const char *plugin_dir;     /* where uploads are written; also searched first */
    const char *allowlist;      /* file of "sha256hex [name]" lines; NULL: refuse uploads */
    const char *plugin_path[MGR_MAX_PLUGIN_PATH];
    size_t n_plugin_path;
    const char *param_names[MGR_MAX_PARAMS], *param_values[MGR_MAX_PARAMS];
    size_t n_params;
    int64_t future_tol_us;      /* --future-tolerance S: data stamped further ahead is dropped */
    int64_t max_clock_jump_us;  /* --max-clock-jump S */
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
    tp_clock clock;             /* SIM.CLOCK or the system clock, under the time rule */
    tp_counts clock_drops;      /* clock readings refused, per reason */
    tp_term clock_term;         /* newest election term of an accepted SIM.CLOCK */
    uint64_t commands_refused;
    size_t max_plan_bytes;      /* MGR_MAX_PLAN_BYTES, or less if the receive buffer cannot hold it */
    int started;
    volatile int stop;
    rx_sub_t *cmd_sub, *upload_sub, *clock_sub;
    mgr_lockstep lockstep;      /* lockstep participation (SIM.CLOCK mode) */
} manager_t;

int manager_parse_args(manager_options *o, int argc, char **argv);
/* Load plan + bindings into a fresh machine; on errors prints them, returns
 * NULL and, if errs is not NULL, leaves them there (for an ack). */
chasm_machine *manager_load(manager_t *mg, const char *name, const char *text, mgr_bindings *out_b, mgr_errors *errs);
/* Mission command and plugin-upload channels. */
int mgr_commands_subscribe(manager_t *mg);
void mgr_commands_unsubscribe(manager_t *mg);
uint64_t mgr_commands_decode_errors(const manager_t *mg);
/* vehicle and utime of a command or upload: 1 when they are this manager's
 * and valid; otherwise refused with an ack and counted. */
int mgr_command_header_ok(manager_t *mg, int64_t utime, const char *vehicle, int32_t seq);

#endif
