/* peer_within: true while another vehicle's latest reported position is
 * within a horizontal radius of this vehicle's (formation keeping, collision
 * avoidance, "wait for the other vehicle"). Pair it with `age` on the peer's
 * variables: a report that stopped coming keeps its last position. */
#include <math.h>

#include "comms.h"

const chasm_param_spec comms_peer_within_params[PW_N_SLOTS] = {
    [PW_PEER_NORTH] = CHASM_READ_REQUIRED("peer_north", CHASM_DOUBLE, "m", "e.g. peer_auv2.north_m"),
    [PW_PEER_EAST] = CHASM_READ_REQUIRED("peer_east", CHASM_DOUBLE, "m", "e.g. peer_auv2.east_m"),
    [PW_RADIUS] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("radius", "m", 0, 1e7, "horizontal distance"),
    [PW_NORTH] = CHASM_READ("north", CHASM_DOUBLE, "m", "nav.north_m", "own position north"),
    [PW_EAST] = CHASM_READ("east", CHASM_DOUBLE, "m", "nav.east_m", "own position east"),
};


int comms_peer_within_evaluate(chasm_ctx *c)
{
    double dn = chasm_read_double(c, PW_PEER_NORTH) - chasm_read_double(c, PW_NORTH);
    double de = chasm_read_double(c, PW_PEER_EAST) - chasm_read_double(c, PW_EAST);
    return hypot(dn, de) <= chasm_param_double(c, PW_RADIUS);
}
