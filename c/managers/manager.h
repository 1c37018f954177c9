/* The manager: one CHASM plan run cyclically on the mission clock, its
 * blackboard bound to LCM channels, commanded over LCM. Navigator, pilot and
 * any other controller are this same program with different plans and
 * bindings (docs/managers.md).
 *
 * This is its API. manager_main.c parses the command line, creates a
 * manager and runs it; mission commands (mgr_commands.c) load, replace and
 * start plans through it. Where the parts are:
 *   manager.c       create, load and replace a plan, requests, destroy
 *   mgr_run.c       the cycle loop and the status it publishes
 *   mgr_clock.c     the mission clock (SIM.CLOCK or the system clock)
 *   mgr_commands.c  mission commands and plugin uploads (mgr_upload.c) */
#ifndef MANAGER_H
#define MANAGER_H

#include <signal.h>

#include <lcm/lcm.h>

#include "chasm/chasm.h"
#include "common/lcm_rx.h"
#include "common/time_policy.h"
#include "managers/mgr_auth.h"
#include "managers/mgr_bindings.h"
#include "managers/mgr_errors.h"
#include "managers/mgr_limits.h"
#include "managers/mgr_lockstep.h"
#include "managers/mgr_options.h"
#include "managers/mgr_status.h"
#include "managers/mgr_structure.h"

/* A plan with its bindings: loaded whole, then adopted or freed whole. */
typedef struct {
    chasm_machine *machine;
    mgr_bindings bindings;
} manager_plan;

typedef struct {
    manager_options opt;        /* the command line, never changed after manager_create */
    chasm_options chasm_opt;    /* how plans load (from opt) */
    lcm_t *lcm;
    manager_plan plan;          /* the running plan */
    mgr_status_ctx status;
    mgr_structure structure;    /* the running plan's, on <VEHICLE>.PLAN.<NAME> */
    int64_t now_us;             /* mission time of the latest clock reading */
    int have_time;
    tp_clock clock;             /* SIM.CLOCK or the system clock, under the time rule */
    tp_counts clock_drops;      /* clock readings refused, per reason */
    tp_term clock_term;         /* newest election term of an accepted SIM.CLOCK */
    uint64_t commands_refused;
    mgr_auth auth;              /* --key-file: commands verified before anything else */
    uint64_t auth_refusals_logged; /* refusals by authentication so far, for the log's rate */
    size_t max_plan_bytes;      /* MGR_MAX_PLAN_BYTES, or less if the receive buffer cannot hold it */
    int waiting_for_start;      /* --wait-start until a CMD_START */
    int started;                /* the running plan has been started */
    volatile sig_atomic_t stop; /* set by a signal or CMD_STOP: leave after this cycle */
    rx_sub_t *cmd_sub, *upload_sub, *clock_sub;
    mgr_lockstep lockstep;      /* lockstep participation (SIM.CLOCK mode) */
} manager_t;

/* Opens LCM, loads the plan and bindings of opt and subscribes everything.
 * 0, or the exit status with nothing left open: 1 the plan or bindings do
 * not load, 2 a bad -D (a usage error, like a bad option) or an LCM failure.
 * mg stays where it is until manager_destroy: handlers keep pointers to it. */
int manager_create(manager_t *mg, const manager_options *opt);
/* Runs cycles until the plan ends (with --exit-on-end) or a stop is
 * requested. The exit status: 0 done or stopped, 2 LCM failed, 3 aborted,
 * 4 failed. */
int manager_run(manager_t *mg);
void manager_destroy(manager_t *mg);

/* Loads a plan (from text, or the file name when text is NULL) and binds it,
 * without touching the running one. 0, or -1 with the errors printed and,
 * when errs is not NULL, kept there (for an ack). */
int manager_load(manager_t *mg, const char *name, const char *text, manager_plan *out, mgr_errors *errs);
/* The running plan goes and p takes its place (p is emptied); the new plan
 * starts like the first one did, once its inputs are ready. -1 when its
 * inputs cannot be subscribed (it is adopted all the same). */
int manager_replace_plan(manager_t *mg, manager_plan *p);
/* Lifts --wait-start. 1 when the plan was already running. */
int manager_request_start(manager_t *mg);
/* Leave after the current cycle. Safe in a signal handler. */
void manager_request_stop(manager_t *mg);

#endif
