/* peer_report: copy the navigation solution into this vehicle's report.
 *
 * The manager publishes the report output every cycle; only a new `seq`
 * makes the modem send it, so the time model sets the reporting period:
 *     do peer_report() every 10 s
 * Each run copies the current navigation values and increments seq; between
 * runs the output keeps the values of the last report, so what the modem
 * sends is what the number stands for. seq is read back from the output
 * variable, so it keeps counting when the state is left and entered again
 * (a repeated number would not be sent). */
#include "comms.h"

/* name, kind, type, unit, required, default, default variable, has_range, min, max, doc */
const chasm_param_spec comms_peer_report_params[PR_N_SLOTS] = {
    {"north", CHASM_READS, CHASM_DOUBLE, "m", 0, 0, "nav.north_m", 0, 0, 0, "own position north"},
    {"east", CHASM_READS, CHASM_DOUBLE, "m", 0, 0, "nav.east_m", 0, 0, 0, "own position east"},
    {"depth", CHASM_READS, CHASM_DOUBLE, "m", 0, 0, "nav.depth_m", 0, 0, 0, "own depth"},
    {"heading", CHASM_READS, CHASM_DOUBLE, "rad", 0, 0, "nav.heading_rad", 0, 0, 0, "own heading"},
    {"speed", CHASM_READS, CHASM_DOUBLE, "m/s", 0, 0, "nav.speed_over_ground_mps", 0, 0, 0, "own speed"},
    {"pitch", CHASM_READS, CHASM_DOUBLE, "rad", 0, 0, NULL, 0, 0, 0, "own pitch (optional)"},
    {"sigma", CHASM_READS, CHASM_DOUBLE, "m", 0, 0, NULL, 0, 0, 0, "own position 1-sigma (optional)"},
    {"label", CHASM_READS, CHASM_STRING, "", 0, 0, NULL, 0, 0, 0,
     "what the vehicle is doing, e.g. a variable each state sets (optional; default: this state's path)"},
    {"out_north", CHASM_WRITES, CHASM_DOUBLE, "m", 0, 0, "report.north_m", 0, 0, 0, NULL},
    {"out_east", CHASM_WRITES, CHASM_DOUBLE, "m", 0, 0, "report.east_m", 0, 0, 0, NULL},
    {"out_depth", CHASM_WRITES, CHASM_DOUBLE, "m", 0, 0, "report.depth_m", 0, 0, 0, NULL},
    {"out_heading", CHASM_WRITES, CHASM_DOUBLE, "rad", 0, 0, "report.heading_rad", 0, 0, 0, NULL},
    {"out_speed", CHASM_WRITES, CHASM_DOUBLE, "m/s", 0, 0, "report.speed_mps", 0, 0, 0, NULL},
    {"out_pitch", CHASM_WRITES, CHASM_DOUBLE, "rad", 0, 0, NULL, 0, 0, 0, "e.g. report.pitch_rad (optional)"},
    {"out_sigma", CHASM_WRITES, CHASM_DOUBLE, "m", 0, 0, NULL, 0, 0, 0,
     "e.g. report.position_sigma_m (optional)"},
    {"out_label", CHASM_WRITES, CHASM_STRING, "", 0, 0, NULL, 0, 0, 0, "e.g. report.active_state (optional)"},
    {"out_seq", CHASM_WRITES, CHASM_INT, "", 0, 0, "report.seq", 0, 0, 0,
     "report number: each new one is sent by the modem"},
};

chasm_status_code comms_peer_report_step(chasm_ctx *c, void *state)
{
    (void)state;
    static const int copies[][2] = {
        {PR_IN_NORTH, PR_OUT_NORTH},     {PR_IN_EAST, PR_OUT_EAST},   {PR_IN_DEPTH, PR_OUT_DEPTH},
        {PR_IN_HEADING, PR_OUT_HEADING}, {PR_IN_SPEED, PR_OUT_SPEED}, {PR_IN_PITCH, PR_OUT_PITCH},
        {PR_IN_SIGMA, PR_OUT_SIGMA},
    };
    for (size_t i = 0; i < CHASM_COUNT(copies); i++)
        chasm_write_double(c, copies[i][1], chasm_read_double(c, copies[i][0]));
    const char *label = chasm_read_string(c, PR_IN_LABEL);
    chasm_write_string(c, PR_OUT_LABEL, label[0] ? label : c->state_path);
    chasm_write_int(c, PR_OUT_SEQ, chasm_read_int(c, PR_OUT_SEQ) + 1);
    return CHASM_RUNNING;
}
