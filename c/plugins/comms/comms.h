/* Plugin `comms`: vehicle-to-vehicle reports over the acoustic modem.
 *
 * peer_report (behavior) fills this vehicle's peer_report_t output and
 * numbers each report; the simulator's modem (or a vehicle's modem driver)
 * sends every new number as one broadcast frame. peer_within (test handler)
 * compares this vehicle's position with another vehicle's latest report.
 * See docs/modem.md. */
#ifndef COMMS_H
#define COMMS_H

#include "chasm/chasm_plugin.h"

/* Slots of peer_report (its schema is indexed by them). */
enum {
    PR_IN_NORTH, PR_IN_EAST, PR_IN_DEPTH, PR_IN_HEADING, PR_IN_SPEED, PR_IN_PITCH, PR_IN_SIGMA, PR_IN_LABEL,
    PR_OUT_NORTH, PR_OUT_EAST, PR_OUT_DEPTH, PR_OUT_HEADING, PR_OUT_SPEED, PR_OUT_PITCH, PR_OUT_SIGMA,
    PR_OUT_LABEL, PR_OUT_SEQ, PR_N_SLOTS
};
extern const chasm_param_spec comms_peer_report_params[PR_N_SLOTS];
chasm_status_code comms_peer_report_step(chasm_ctx *c, void *state);

/* Slots of peer_within. */
enum { PW_PEER_NORTH, PW_PEER_EAST, PW_RADIUS, PW_NORTH, PW_EAST, PW_N_SLOTS };
extern const chasm_param_spec comms_peer_within_params[PW_N_SLOTS];
int comms_peer_within_evaluate(chasm_ctx *c);

#endif
