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
    [PR_IN_NORTH] = CHASM_READ("north", CHASM_DOUBLE, "m", "nav.north_m", "own position north"),
    [PR_IN_EAST] = CHASM_READ("east", CHASM_DOUBLE, "m", "nav.east_m", "own position east"),
    [PR_IN_DEPTH] = CHASM_READ("depth", CHASM_DOUBLE, "m", "nav.depth_m", "own depth"),
    [PR_IN_HEADING] = CHASM_READ("heading", CHASM_DOUBLE, "rad", "nav.heading_rad", "own heading"),
    [PR_IN_SPEED] = CHASM_READ("speed", CHASM_DOUBLE, "m/s", "nav.speed_over_ground_mps", "own speed"),
    [PR_IN_PITCH] = CHASM_READ("pitch", CHASM_DOUBLE, "rad", NULL, "own pitch (optional)"),
    [PR_IN_SIGMA] = CHASM_READ("sigma", CHASM_DOUBLE, "m", NULL, "own position 1-sigma (optional)"),
    [PR_IN_LABEL] = CHASM_READ("label", CHASM_STRING, "", NULL,
                               "what the vehicle is doing, e.g. a variable each state sets (optional; default: this "
                               "state's path)"),
    [PR_OUT_NORTH] = CHASM_WRITE("out_north", CHASM_DOUBLE, "m", "report.north_m", NULL),
    [PR_OUT_EAST] = CHASM_WRITE("out_east", CHASM_DOUBLE, "m", "report.east_m", NULL),
    [PR_OUT_DEPTH] = CHASM_WRITE("out_depth", CHASM_DOUBLE, "m", "report.depth_m", NULL),
    [PR_OUT_HEADING] = CHASM_WRITE("out_heading", CHASM_DOUBLE, "rad", "report.heading_rad", NULL),
    [PR_OUT_SPEED] = CHASM_WRITE("out_speed", CHASM_DOUBLE, "m/s", "report.speed_mps", NULL),
    [PR_OUT_PITCH] = CHASM_WRITE("out_pitch", CHASM_DOUBLE, "rad", NULL, "e.g. report.pitch_rad (optional)"),
    [PR_OUT_SIGMA] = CHASM_WRITE("out_sigma", CHASM_DOUBLE, "m", NULL, "e.g. report.position_sigma_m (optional)"),
    [PR_OUT_LABEL] = CHASM_WRITE("out_label", CHASM_STRING, "", NULL, "e.g. report.active_state (optional)"),
    [PR_OUT_SEQ] = CHASM_WRITE("out_seq", CHASM_INT, "", "report.seq",
                               "report number: each new one is sent by the modem"),
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
