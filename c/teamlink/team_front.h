/* The team link's front summary (message `front`, team_link.schema) made from a
 * vehicle's own front estimate: one copy for both of its writers, the
 * navigator's team_link (c/plugins/team, which sends it) and auv-front-estimate
 * (c/frontest/front_summary.cpp, whose tests hold it to the fit).
 *
 * The parameters are left for the codec to round to their steps; each sigma is
 * first rounded UP to its step (a quantised sigma never claims more than the
 * fit did), the two waters' sigmas sent as the larger; the sample count
 * saturates at the field's maximum. An estimate outside the schema's ranges (a
 * sigma over 25.5 m, a width over 409.5 m) is not sent: the codec refuses it
 * rather than clamping, and a clamped sigma would claim too much. */
#ifndef TEAM_FRONT_H
#define TEAM_FRONT_H

#include "team/team_codec.h"

typedef struct {
    int vehicle;        /* team index */
    double mission_s;   /* mission time of the estimate */
    double offset_m, angle_rad, ta_c, tb_c, width_m;
    double offset_sigma_m, angle_sigma_rad, ta_sigma_c, tb_sigma_c, width_sigma_m;
    int samples;
} team_front_estimate;

/* 1 and *out filled when the estimate can be sent, 0 when not (out of range). */
int team_front_summary(const team_front_estimate *e, team_msg_front *out);
/* A summary's sigma with its parameter's quantisation added (uniform over a
 * step: variance step^2 / 12), for the receiver. `param` is a field name. */
double team_front_sigma_received(const char *param, double sigma);

#endif
