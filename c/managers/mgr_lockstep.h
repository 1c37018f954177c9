/* Lockstep participation of a manager (docs/multihil.md).
 *
 * When the world's SIM.CLOCK says MODE_LOCKSTEP, the environment server
 * advances global time one step only after every registered participant
 * reported that step done. A manager registers as "<VEHICLE>.<NAME>" on
 * SIM.LOCKSTEP (repeated each second until it hears any clock), and reports
 * step n once the cycle that the clock of step n triggered has published its
 * outputs: the next loop iteration. A repeated step (a new server resumes
 * the step it found in flight) is confirmed again without a second cycle.
 * A datagram lost under load cannot stop the world: while no newer clock
 * comes, the last report is repeated every MGR_LOCKSTEP_RESEND_MS (reports
 * are keyed by step, so a repeat is counted once; the server republishes a
 * clock that a repeated report shows was missed).
 * Free-running clocks need nothing of this: it stays silent. */
#ifndef MGR_LOCKSTEP_H
#define MGR_LOCKSTEP_H

#include <lcm/lcm.h>
#include <stdint.h>

#include "auv/auv_sim_clock_t.h"

#define MGR_LOCKSTEP_RESEND_MS 250

typedef struct {
    char name[96];
    int seen_clock;             /* any SIM.CLOCK heard: registration is over */
    int lockstep;               /* the latest clock was a lockstep clock */
    int64_t pending_step;       /* step whose cycle is under way, -1: none */
    int64_t pending_utime;
    int64_t last_done;          /* last step reported, -1: none */
    int64_t last_done_utime;    /* its global time */
    int64_t next_register_ms;   /* monotonic */
    int64_t next_resend_ms;     /* monotonic: repeat the last report from then on */
    int64_t resent;             /* reports repeated (lost datagrams, slow steps) */
} mgr_lockstep;

void mgr_lockstep_init(mgr_lockstep *ls, const char *vehicle, const char *name);
/* Every SIM.CLOCK message, as it is handled. */
void mgr_lockstep_on_clock(mgr_lockstep *ls, lcm_t *lcm, const auv_sim_clock_t *c);
/* In a lockstep world a cycle (or a LOADING status) may run only for the step
 * whose clock was just handled, never on another message arriving later:
 * otherwise its outputs could reach others after the next step began. */
int mgr_lockstep_may_cycle(const mgr_lockstep *ls);
/* Top of each loop iteration: register, or report the step the last one finished. */
void mgr_lockstep_poll(mgr_lockstep *ls, lcm_t *lcm);
/* The manager leaves: the server stops waiting for it. */
void mgr_lockstep_leave(mgr_lockstep *ls, lcm_t *lcm);

#endif
