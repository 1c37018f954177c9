/* peer_within: true while another vehicle's latest reported position is
 * within a horizontal radius of this vehicle's (formation keeping, collision
 * avoidance, "wait for the other vehicle"). Pair it with `age` on the peer's
 * variables: a report that stopped coming keeps its last position. */
#include <math.h>

#include "comms.h"

const chasm_param_spec comms_peer_within_params[PW_N_SLOTS] = {
    {"peer_north", CHASM_READS, CHASM_DOUBLE, "m", 1, 0, NULL, 0, 0, 0, "e.g. peer_auv2.north_m"},
    {"peer_east", CHASM_READS, CHASM_DOUBLE, "m", 1, 0, NULL, 0, 0, 0, "e.g. peer_auv2.east_m"},
    {"radius", CHASM_PARAM, CHASM_DOUBLE, "m", 1, 0, NULL, 1, 0, 1e7, "horizontal distance"},
    {"north", CHASM_READS, CHASM_DOUBLE, "m", 0, 0, "nav.north_m", 0, 0, 0, "own position north"},
    {"east", CHASM_READS, CHASM_DOUBLE, "m", 0, 0, "nav.east_m", 0, 0, 0, "own position east"},
};

int comms_peer_within_evaluate(chasm_ctx *c)
{
    double dn = chasm_read_double(c, PW_PEER_NORTH) - chasm_read_double(c, PW_NORTH);
    double de = chasm_read_double(c, PW_PEER_EAST) - chasm_read_double(c, PW_EAST);
    return hypot(dn, de) <= chasm_param_double(c, PW_RADIUS);
}
